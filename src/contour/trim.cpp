// Trimming a closed isosurface to the part the samples support (contour.h):
// the iso-line g = distance of the local sample spacing cut through the
// triangles, as marching tetrahedra cuts tets one dimension up. Not in the
// paper; the peers trim by removing whole triangles of low density
// (PoissonRecon's SurfaceTrimmer, Open3D's quantile filter), which leaves a
// jagged rim.
#include <pdd/contour.h>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/nearest_neighbors.h"
#include "common/union_find.h"
#include "contour/angles.h"
#include "contour/components.h"
#include "contour/rim.h"
#include "contour/spacing.h"

namespace pdd {

namespace {

using detail::find_root;
using detail::singletons;

// Undirected edges of the mesh (a < b), sorted, and each vertex's neighbours.
std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> around(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      around[f[i]].push_back(f[(i + 1) % 3]);
      around[f[i]].push_back(f[(i + 2) % 3]);
    }
  for (auto& a : around) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return around;
}

double area(const TriangleMesh& mesh) {
  double total = 0;
  for (const auto& f : mesh.faces)
    total += 0.5 * (mesh.vertices[f[1]] - mesh.vertices[f[0]])
                       .cross(mesh.vertices[f[2]] - mesh.vertices[f[0]])
                       .norm();
  return total;
}

enum State : char { kIn = 0, kOn = 1, kOut = 2 };

// The cut's rim made smooth: ears (triangles with two boundary edges, a
// zigzag of the rim) whose smallest angle is under 30 degrees go, then each
// rim vertex moves halfway to the midpoint of its two rim neighbours (twice),
// which stays on the surface to second order where the rim is smooth. Unused
// vertices are dropped.
// The edges (a < b) that one face of `mesh` has, sorted (a mesh's worth of
// pairs sorted, not a map of them: millions of faces at scale).
std::vector<std::pair<int, int>> boundary_edges(const TriangleMesh& mesh) {
  std::vector<std::pair<int, int>> all;
  all.reserve(3 * mesh.faces.size());
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i)
      all.emplace_back(std::min(f[i], f[(i + 1) % 3]), std::max(f[i], f[(i + 1) % 3]));
  std::sort(all.begin(), all.end());
  std::vector<std::pair<int, int>> once;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j] == all[i]) ++j;
    if (j - i == 1) once.push_back(all[i]);
    i = j;
  }
  return once;
}

void smooth_boundary(TriangleMesh& mesh) {
  for (int pass = 0; pass < 3; ++pass) {
    const std::vector<std::pair<int, int>> rim_edges = boundary_edges(mesh);
    auto on_rim = [&](int a, int b) {
      return std::binary_search(rim_edges.begin(), rim_edges.end(),
                                std::pair<int, int>(std::min(a, b), std::max(a, b)));
    };
    std::vector<std::array<int, 3>> kept;
    for (const auto& f : mesh.faces) {
      int open = 0;
      for (int i = 0; i < 3; ++i) open += on_rim(f[i], f[(i + 1) % 3]);
      const auto& x = mesh.vertices;
      if (open == 2 && detail::min_angle_degrees(x[f[0]], x[f[1]], x[f[2]]) < 30) continue;
      kept.push_back(f);
    }
    if (kept.size() == mesh.faces.size()) break;
    mesh.faces = std::move(kept);
  }
  std::vector<std::vector<int>> rim(mesh.vertices.size());
  for (const auto& [a, b] : boundary_edges(mesh)) {
    rim[a].push_back(b);
    rim[b].push_back(a);
  }
  for (int round = 0; round < 2; ++round) {
    std::vector<Vec3> moved = mesh.vertices;
    for (std::size_t v = 0; v < rim.size(); ++v)
      if (rim[v].size() == 2)
        moved[v] = 0.5 * mesh.vertices[v] +
                   0.25 * (mesh.vertices[rim[v][0]] + mesh.vertices[rim[v][1]]);
    mesh.vertices = std::move(moved);
  }
  detail::drop_unused_vertices(mesh);
}

}  // namespace

int boundary_loops(const TriangleMesh& mesh) {
  // Loops: the components of the boundary edges through shared vertices.
  std::vector<int> parent = singletons(mesh.vertices.size());
  std::vector<char> on_boundary(mesh.vertices.size(), 0);
  for (const auto& [a, b] : boundary_edges(mesh)) {
    on_boundary[a] = on_boundary[b] = 1;
    parent[find_root(parent, a)] = find_root(parent, b);
  }
  int loops = 0;
  for (std::size_t v = 0; v < parent.size(); ++v)
    if (on_boundary[v] && find_root(parent, static_cast<int>(v)) == static_cast<int>(v)) ++loops;
  return loops;
}

TrimReport trim_to_samples(TriangleMesh& mesh, const std::vector<Vec3>& samples,
                           const TrimOptions& options) {
  for (const auto& [value, name] : {std::pair(options.distance, "distance"),
                                    std::pair(options.holes, "holes"),
                                    std::pair(options.islands, "islands")})
    if (!(value >= 0) || !std::isfinite(value))
      throw std::invalid_argument(std::string("trim_to_samples: ") + name +
                                  " must be a number >= 0");
  TrimReport report;
  if (options.distance == 0 || mesh.faces.empty()) return report;
  if (samples.size() < 2) throw std::invalid_argument("trim_to_samples: fewer than two samples");
  report.trimmed = true;
  const double area_before = area(mesh);

  // g at each vertex: its distance to the nearest sample in that sample's
  // local spacings, then smoothed over the mesh so that the cut is a smooth curve.
  const detail::NearestNeighbors tree(samples);
  const detail::Spacing spacing = detail::sample_spacing(samples, tree, 8);
  report.spacing = spacing.average;
  const std::size_t n = mesh.vertices.size();
  // The distance inside a triangle exceeds that at its corners where it runs
  // between samples: each vertex takes the largest of its own and those of
  // the midpoints of its edges.
  const std::vector<std::vector<int>> around = vertex_neighbours(mesh);
  auto distance = [&](const Vec3& x) {
    const int j = tree.query(x, 1)[0];
    return (x - samples[j]).norm() / spacing.local[j];
  };
  std::vector<double> g(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) { g[v] = distance(mesh.vertices[v]); });
  std::vector<std::pair<int, int>> edges;
  for (std::size_t v = 0; v < n; ++v)
    for (int w : around[v])
      if (static_cast<int>(v) < w) edges.emplace_back(static_cast<int>(v), w);
  std::vector<double> at_midpoint(edges.size());
  tbb::parallel_for(std::size_t(0), edges.size(), [&](std::size_t e) {
    at_midpoint[e] =
        distance(0.5 * (mesh.vertices[edges[e].first] + mesh.vertices[edges[e].second]));
  });
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (int v : {edges[e].first, edges[e].second}) g[v] = std::max(g[v], at_midpoint[e]);
  std::vector<double> lengths(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    lengths[e] = (mesh.vertices[edges[e].first] - mesh.vertices[edges[e].second]).norm();
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const double median_edge = lengths.empty() ? 0 : lengths[lengths.size() / 2];
  for (int round = 0; round < 2; ++round) {
    std::vector<double> smoothed(n);
    for (std::size_t v = 0; v < n; ++v) {
      double sum = 0;
      for (int w : around[v]) sum += g[w];
      smoothed[v] = around[v].empty() ? g[v] : 0.5 * g[v] + 0.5 * sum / around[v].size();
    }
    g = std::move(smoothed);
  }
  // The midpoints and the smoothing raise g by about an edge over the
  // samples' distance: around a lone sample whose reach is a few edges (a
  // scan's sparse edge) they lift the whole disc over T. Each sample's
  // nearest vertex keeps its own distance, so that its foot stays on the surface.
  {
    const detail::NearestNeighbors on_mesh(mesh.vertices);
    std::vector<int> foot(samples.size());
    tbb::parallel_for(std::size_t(0), samples.size(),
                      [&](std::size_t j) { foot[j] = on_mesh.query(samples[j], 1)[0]; });
    for (std::size_t j = 0; j < samples.size(); ++j)
      g[foot[j]] =
          std::min(g[foot[j]], (mesh.vertices[foot[j]] - samples[j]).norm() / spacing.local[j]);
  }
  const double T = options.distance;
  std::vector<char> state(n);
  for (std::size_t v = 0; v < n; ++v) state[v] = g[v] < T ? kIn : kOut;

  // Unsupported regions smaller than `holes` spacings across are a scan's
  // gaps: they stay closed.
  {
    std::vector<int> parent = singletons(n);
    for (std::size_t v = 0; v < n; ++v)
      if (state[v] == kOut)
        for (int w : around[v])
          if (state[w] == kOut) parent[find_root(parent, static_cast<int>(v))] = find_root(parent, w);
    std::vector<Eigen::AlignedBox3d> box(n);
    for (std::size_t v = 0; v < n; ++v)
      if (state[v] == kOut) box[find_root(parent, static_cast<int>(v))].extend(mesh.vertices[v]);
    std::vector<char> small(n, 0);
    for (std::size_t r = 0; r < n; ++r)
      if (!box[r].isEmpty() && box[r].diagonal().norm() < options.holes * spacing.average) {
        small[r] = 1;
        ++report.holes_kept;
      }
    for (std::size_t v = 0; v < n; ++v)
      if (state[v] == kOut && small[find_root(parent, static_cast<int>(v))]) state[v] = kIn;
  }

  // Snapping: a vertex whose nearest crossing lies within a quarter of its edge
  // takes the iso-line through itself, so that the cut makes no sliver; only
  // where its link crosses the line twice (the cut stays manifold) and no
  // neighbour did the same.
  auto crossing = [&](int a, int b) {  // parameter from a to b of g = T
    return (T - g[a]) / (g[b] - g[a]);
  };
  constexpr double kSnap = 0.25;
  // Sign changes around each vertex's link (a neighbour that snaps stops v
  // from snapping, so the states of the link, out or not, stay those counted here).
  std::vector<int> changes(n, 0);
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i)
      changes[f[i]] += (state[f[(i + 1) % 3]] == kOut) != (state[f[(i + 2) % 3]] == kOut);
  for (std::size_t v = 0; v < n; ++v) {
    double nearest = 1;
    bool neighbour_on = false;
    for (int w : around[v]) {
      neighbour_on = neighbour_on || state[w] == kOn;
      if ((state[v] == kIn) == (state[w] == kOut) && state[w] != kOn) {
        const double t = crossing(static_cast<int>(v), w);
        nearest = std::min(nearest, state[v] == kIn ? t : 1 - t);
      }
    }
    if (!neighbour_on && nearest < kSnap && changes[v] == 2) state[v] = kOn;
  }

  // The cut: each triangle clipped to its kept part (in and on vertices),
  // one new vertex per crossed edge, quadrangles split along the shorter diagonal.
  TriangleMesh cut;
  std::vector<int> index(n, -1);
  auto keep_vertex = [&](int v) {
    if (index[v] < 0) {
      index[v] = static_cast<int>(cut.vertices.size());
      cut.vertices.push_back(mesh.vertices[v]);
    }
    return index[v];
  };
  std::map<std::pair<int, int>, int> crossings;
  auto cross = [&](int a, int b) {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    const auto found = crossings.find(key);
    if (found != crossings.end()) return found->second;
    const double t = crossing(key.first, key.second);
    const int id = static_cast<int>(cut.vertices.size());
    cut.vertices.push_back(mesh.vertices[key.first] +
                           t * (mesh.vertices[key.second] - mesh.vertices[key.first]));
    crossings.emplace(key, id);
    return id;
  };
  for (const auto& f : mesh.faces) {
    int outside = 0, inside = 0;
    for (int v : f) {
      outside += state[v] == kOut;
      inside += state[v] == kIn;
    }
    if (inside == 0) continue;  // nothing of it is supported (or only its on corners)
    if (outside == 0) {
      cut.faces.push_back({keep_vertex(f[0]), keep_vertex(f[1]), keep_vertex(f[2])});
      continue;
    }
    std::vector<int> polygon;
    for (int i = 0; i < 3; ++i) {
      const int a = f[i], b = f[(i + 1) % 3];
      if (state[a] != kOut) polygon.push_back(keep_vertex(a));
      if ((state[a] == kIn && state[b] == kOut) || (state[a] == kOut && state[b] == kIn))
        polygon.push_back(cross(a, b));
    }
    if (polygon.size() == 3) {
      cut.faces.push_back({polygon[0], polygon[1], polygon[2]});
    } else if (polygon.size() == 4) {
      const auto& x = cut.vertices;
      if ((x[polygon[0]] - x[polygon[2]]).squaredNorm() <=
          (x[polygon[1]] - x[polygon[3]]).squaredNorm()) {
        cut.faces.push_back({polygon[0], polygon[1], polygon[2]});
        cut.faces.push_back({polygon[0], polygon[2], polygon[3]});
      } else {
        cut.faces.push_back({polygon[0], polygon[1], polygon[3]});
        cut.faces.push_back({polygon[1], polygon[2], polygon[3]});
      }
    }
  }

  // Islands: pieces of the cut surface less than `islands` spacings across
  // that fewer than kIslandSamples samples have as their nearest piece (a
  // stray's disc, a sheet behind a thin wall). A small piece that more samples
  // lie on is scanned surface (a scan's sparse edge): dropping it would leave
  // those samples far from the surface.
  if (!cut.faces.empty()) {
    constexpr int kIslandSamples = 2;
    const detail::Components c = detail::components(cut);
    const std::vector<Eigen::AlignedBox3d> box = detail::component_boxes(cut, c);
    std::vector<char> small(cut.vertices.size(), 0);
    for (std::size_t r = 0; r < small.size(); ++r)
      small[r] = c.faces[r] > 0 && box[r].diagonal().norm() < options.islands * spacing.average;
    std::vector<int> support(cut.vertices.size(), 0);
    if (std::find(small.begin(), small.end(), 1) != small.end()) {
      const detail::NearestNeighbors on_cut(cut.vertices);  // all used: made by the faces
      std::vector<int> nearest_root(samples.size());
      tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t i) {
        nearest_root[i] = c.root_of[on_cut.query(samples[i], 1)[0]];
      });
      for (int r : nearest_root) ++support[r];
    }
    std::vector<char> drop(cut.vertices.size(), 0);
    for (std::size_t r = 0; r < drop.size(); ++r) drop[r] = small[r] && support[r] < kIslandSamples;
    report.islands = detail::remove_marked(cut, c, drop);
  }
  smooth_boundary(cut);
  detail::remesh_rim(cut, boundary_edges(cut), median_edge);
  mesh = std::move(cut);
  report.area_removed = area_before > 0 ? 1 - area(mesh) / area_before : 0;
  report.boundary_loops = boundary_loops(mesh);
  return report;
}

}  // namespace pdd
