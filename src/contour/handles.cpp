// Handles of the output that the samples do not support (contour.h): where a
// wall is thinner than the sample spacing f can leave a tunnel through it, and
// where a gap is narrower, a bridge across it (docs/benchmarks.md, "Spurious
// handles"). Both are tubes whose faces lie near samples but face across
// their normals; such a tube is cut where it is found and the two ends capped
// with CGAL's hole filling (refined and faired).
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <pdd/contour.h>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"
#include "contour/components.h"
#include "contour/spacing.h"

namespace pdd {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

constexpr double kPi = 3.14159265358979323846;

// Per face: 1 when samples lie within `radius` of its centroid but none of
// their normals is within the angle of its own (the face crosses the data),
// 0 otherwise (supported, or no sample near: a hole in the data, not a
// contradiction of it).
std::vector<char> unsupported_faces(const TriangleMesh& mesh, const PointSet& samples,
                                    const detail::NearestNeighbors& tree, double radius,
                                    double degrees) {
  const double min_cosine = std::cos(degrees * kPi / 180.0);
  std::vector<char> unsupported(mesh.faces.size(), 0);
  tbb::parallel_for(std::size_t(0), mesh.faces.size(), [&](std::size_t k) {
    const auto& f = mesh.faces[k];
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3 n = (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a);
    if (!(n.norm() > 0)) return;
    const Vec3 centroid = (a + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
    const int nearest = tree.query(centroid, 1).front();  // most faces: supported by it alone
    if ((samples.points[nearest] - centroid).norm() > radius) return;
    if (samples.normals[nearest].dot(n) > min_cosine * n.norm() * samples.normals[nearest].norm())
      return;
    bool near = false;
    for (int j : tree.query(centroid, 16)) {
      if ((samples.points[j] - centroid).norm() > radius) break;
      near = true;
      if (samples.normals[j].dot(n) > min_cosine * n.norm() * samples.normals[j].norm()) return;
    }
    unsupported[k] = near ? 1 : 0;
  });
  return unsupported;
}

// Each face's three neighbours across its edges (-1 on a boundary edge):
// neighbour i is across the edge from corner i to corner i + 1.
std::vector<std::array<int, 3>> face_neighbours(const TriangleMesh& mesh) {
  std::vector<std::array<int, 4>> halfedges;  // (from, to, face, corner)
  for (int k = 0; k < static_cast<int>(mesh.faces.size()); ++k)
    for (int i = 0; i < 3; ++i) {
      const int u = mesh.faces[k][i], w = mesh.faces[k][(i + 1) % 3];
      halfedges.push_back({std::min(u, w), std::max(u, w), k, i});
    }
  tbb::parallel_sort(halfedges.begin(), halfedges.end());
  std::vector<std::array<int, 3>> across(mesh.faces.size(), {-1, -1, -1});
  for (std::size_t i = 0; i + 1 < halfedges.size(); ++i) {
    const auto& a = halfedges[i];
    const auto& b = halfedges[i + 1];
    if (a[0] == b[0] && a[1] == b[1]) {
      across[a[2]][a[3]] = b[2];
      across[b[2]][b[3]] = a[2];
    }
  }
  return across;
}

// Lists by vertex in compressed rows: at a million vertices, a std::vector
// each costs more to allocate than to fill.
struct Rows {
  std::vector<int> offsets;  // |V| + 1
  std::vector<int> items;
  struct Range {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
  };
  Range operator[](int v) const {
    return {items.data() + offsets[v], items.data() + offsets[v + 1]};
  }
};

// The faces around each vertex, in increasing order.
Rows faces_around_vertices(const TriangleMesh& mesh) {
  const int n = static_cast<int>(mesh.vertices.size());
  Rows rows;
  rows.offsets.assign(n + 1, 0);
  for (const auto& f : mesh.faces)
    for (int v : f) ++rows.offsets[v + 1];
  for (int v = 0; v < n; ++v) rows.offsets[v + 1] += rows.offsets[v];
  rows.items.resize(rows.offsets[n]);
  std::vector<int> fill(rows.offsets.begin(), rows.offsets.end() - 1);
  for (int k = 0; k < static_cast<int>(mesh.faces.size()); ++k)
    for (int v : mesh.faces[k]) rows.items[fill[v]++] = k;
  return rows;
}

// Faces around each vertex, and the faces across each edge.
struct Adjacency {
  Rows vertex_faces;
  std::vector<std::array<int, 3>> across;  // face_neighbours
  explicit Adjacency(const TriangleMesh& mesh)
      : vertex_faces(faces_around_vertices(mesh)), across(face_neighbours(mesh)) {}
};

// The faces of `in` (a mask) in groups connected through shared edges,
// each group in increasing face order, groups by their first face.
std::vector<std::vector<int>> edge_connected(const Adjacency& adj,
                                             const std::vector<char>& in) {
  std::vector<std::vector<int>> groups;
  std::vector<char> seen(in.size(), 0);
  for (int start = 0; start < static_cast<int>(in.size()); ++start) {
    if (!in[start] || seen[start]) continue;
    std::vector<int> group{start}, stack{start};
    seen[start] = 1;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      for (int g : adj.across[k])
        if (g >= 0 && in[g] && !seen[g]) {
          seen[g] = 1;
          group.push_back(g);
          stack.push_back(g);
        }
    }
    std::sort(group.begin(), group.end());
    groups.push_back(std::move(group));
  }
  return groups;
}

// Whether the faces reached from `first` and those from `second` are one
// piece: two breadth-first searches in turn, through the edges that
// `passable(face, corner)` opens, until they meet (one piece) or one runs out
// (separated), so that the cost follows the smaller side or the distance
// between the two. `side` is all zero, and is left so.
template <class Passable>
bool sides_meet(const std::vector<std::array<int, 3>>& across, const std::vector<int>& first,
                const std::vector<int>& second, std::vector<char>& side, Passable passable) {
  std::array<std::vector<int>, 2> queue{std::vector<int>{}, std::vector<int>{}};
  std::array<std::size_t, 2> head{0, 0};
  std::vector<int> touched;
  bool met = false;
  const auto reach = [&](int k, int s) {
    if (side[k] == 0) {
      side[k] = static_cast<char>(s + 1);
      touched.push_back(k);
      queue[s].push_back(k);
    } else if (side[k] != s + 1) {
      met = true;
    }
  };
  for (int k : first) reach(k, 0);
  for (int k : second) reach(k, 1);
  bool separated = queue[0].empty() || queue[1].empty();
  while (!met && !separated)
    for (int s = 0; s < 2 && !met; ++s) {
      if (head[s] == queue[s].size()) {
        separated = true;
        break;
      }
      const int k = queue[s][head[s]++];
      for (int i = 0; i < 3 && !met; ++i) {
        const int g = across[k][i];
        if (g >= 0 && passable(k, i)) reach(g, s);
      }
    }
  for (int k : touched) side[k] = 0;
  return met;
}

// Whether the faces of `band` (marked in `in_band`) form an annulus around a
// tube of the mesh: Euler characteristic 0, one edge-connected piece, two
// simple boundary loops that share no vertex, every boundary edge inner to
// the mesh; `loop_of` gets each boundary vertex's loop, 1 or 2. Local: the
// cost follows the band's size.
bool is_annulus(const TriangleMesh& mesh, const Adjacency& adj, const std::vector<int>& band,
                const std::vector<char>& in_band, std::map<int, char>& loop_of) {
  std::vector<std::pair<int, int>> edges;
  std::vector<int> vertices;
  for (int k : band)
    for (int i = 0; i < 3; ++i) {
      if (adj.across[k][i] < 0) return false;  // on the mesh's own boundary
      edges.push_back(std::minmax(mesh.faces[k][i], mesh.faces[k][(i + 1) % 3]));
      vertices.push_back(mesh.faces[k][i]);
    }
  std::sort(edges.begin(), edges.end());
  std::sort(vertices.begin(), vertices.end());
  const long distinct_vertices = std::unique(vertices.begin(), vertices.end()) - vertices.begin();
  std::vector<std::pair<int, int>> rim_edges;  // the edges of one band face only
  long distinct_edges = 0;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    ++distinct_edges;
    if (j - i == 1) rim_edges.push_back(edges[i]);
    i = j;
  }
  if (distinct_vertices - distinct_edges + static_cast<long>(band.size()) != 0) return false;
  std::map<int, std::vector<int>> rim;  // boundary vertex -> its boundary neighbours
  for (const auto& e : rim_edges) {
    rim[e.first].push_back(e.second);
    rim[e.second].push_back(e.first);
  }
  int loops = 0;
  loop_of.clear();
  for (const auto& [v, next] : rim) {
    if (next.size() != 2) return false;  // loops touching at v
    if (loop_of[v]) continue;
    if (++loops > 2) return false;
    std::vector<int> stack{v};
    loop_of[v] = static_cast<char>(loops);
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      for (int w : rim[u])
        if (!loop_of[w]) {
          loop_of[w] = static_cast<char>(loops);
          stack.push_back(w);
        }
    }
  }
  if (loops != 2) return false;
  std::map<int, char> reached{{band.front(), 1}};  // one piece through shared edges
  std::vector<int> stack{band.front()};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    for (int g : adj.across[k])
      if (g >= 0 && in_band[g] && !reached[g]) {
        reached[g] = 1;
        stack.push_back(g);
      }
  }
  return reached.size() == band.size();
}

// The mesh without the removed faces, each of its new holes filled.
bool cap_holes(TriangleMesh& mesh, const std::vector<char>& removed) {
  Mesh m;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) vertex.push_back(m.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (std::size_t k = 0; k < mesh.faces.size(); ++k) {
    if (removed[k]) continue;
    const auto& f = mesh.faces[k];
    if (m.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]) == Mesh::null_face()) return false;
  }
  std::vector<char> cut(mesh.vertices.size(), 0);  // the vertices of the removed faces
  for (std::size_t k = 0; k < mesh.faces.size(); ++k)
    if (removed[k])
      for (int v : mesh.faces[k]) cut[v] = 1;
  std::vector<Mesh::Halfedge_index> holes;  // the new ones only: the mesh's own boundary stays
  std::vector<char> seen(m.number_of_halfedges(), 0);
  for (Mesh::Halfedge_index h : m.halfedges())
    if (m.is_border(h) && !seen[h.idx()] && cut[m.target(h).idx()]) {
      holes.push_back(h);
      for (Mesh::Halfedge_index g : CGAL::halfedges_around_face(h, m)) seen[g.idx()] = 1;
    }
  for (Mesh::Halfedge_index h : holes) {
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> added;
    const auto result = CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole(
        m, h, std::back_inserter(faces), std::back_inserter(added));
    if (!std::get<0>(result)) return false;
  }
  for (Mesh::Vertex_index v : m.vertices())
    if (m.is_isolated(v)) m.remove_vertex(v);
  m.collect_garbage();
  TriangleMesh out;
  for (Mesh::Vertex_index v : m.vertices()) {
    const auto& p = m.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (Mesh::Face_index f : m.faces()) {
    std::array<int, 3> t{};
    int i = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m)) t[i++] = static_cast<int>(v.idx());
    out.faces.push_back(t);
  }
  mesh = std::move(out);
  return true;
}

// One pass over the cycles of three edges that bound no face and do not
// separate the mesh (handles whose waist is a single triangle's worth, below
// any resolution): each is cut, and both sides closed with a triangle. A
// cycle is tested on the mesh as the pass found it, with the cycles already
// cut this pass as barriers; one that touches the faces of such a cut waits
// for the next pass (`deferred`). Returns the cuts.
int cut_triangle_waists_once(TriangleMesh& mesh, bool& deferred) {
  const std::vector<std::array<int, 3>> across = face_neighbours(mesh);
  // Around each vertex u: its faces, and the sorted distinct w of the edges u w
  // that they run.
  const Rows stars = faces_around_vertices(mesh);
  const auto next_of = [&](int u, int k) {
    const auto& f = mesh.faces[k];
    return f[0] == u ? f[1] : f[1] == u ? f[2] : f[0];
  };
  const int nv = static_cast<int>(mesh.vertices.size());
  Rows neighbours;
  neighbours.offsets.assign(nv + 1, 0);
  neighbours.items.resize(stars.items.size());
  for (int u = 0; u < nv; ++u) {
    const auto first = neighbours.items.begin() + neighbours.offsets[u];
    auto last = first;
    for (int k : stars[u]) *last++ = next_of(u, k);
    std::sort(first, last);
    neighbours.offsets[u + 1] =
        neighbours.offsets[u] + static_cast<int>(std::unique(first, last) - first);
  }
  const auto left_face = [&](int u, int w) {  // the face that runs u w
    for (int k : stars[u])
      if (next_of(u, k) == w) return k;
    return -1;
  };
  const auto runs = [&](int u, int w) { return left_face(u, w) >= 0; };
  const auto edge = [](int u, int w) { return std::pair<int, int>(std::min(u, w), std::max(u, w)); };
  struct Cut {
    std::array<int, 3> cycle;
    std::vector<int> right;  // the faces at the cycle on its right side
  };
  std::vector<Cut> cuts;
  std::vector<std::pair<int, int>> barriers;  // the edges of this pass's cuts
  std::vector<char> side(mesh.faces.size(), 0), near_cut(mesh.vertices.size(), 0),
      on_barrier(mesh.vertices.size(), 0);
  deferred = false;
  for (int a = 0; a < static_cast<int>(mesh.vertices.size()); ++a) {
    if (a % 65536 == 0) detail::poll();
    const Rows::Range around_a = neighbours[a];
    for (int b : around_a) {
      if (b <= a) continue;
      for (int c : neighbours[b]) {
        if (c <= b || !std::binary_search(around_a.begin(), around_a.end(), c)) continue;
        // Oriented a -> b -> c -> a along the faces on its left; a face (in either
        // orientation) on it, or an edge with other than two faces: not a waist.
        // (Most such cycles are faces: that test first.)
        const int left = left_face(a, b), right = left_face(b, a);
        if (left < 0 || right < 0) continue;
        const auto has = [&](int k) {
          const auto& f = mesh.faces[k];
          return std::count(f.begin(), f.end(), a) + std::count(f.begin(), f.end(), b) +
                     std::count(f.begin(), f.end(), c) == 3;
        };
        if (has(left) || has(right)) continue;
        if (!(runs(b, c) && runs(c, b) && runs(c, a) && runs(a, c))) continue;
        if (near_cut[a] || near_cut[b] || near_cut[c]) {
          deferred = true;
          continue;
        }
        const auto crosses = [&](int k, int i) {  // the edge is on this cycle or a cut one
          const int u = mesh.faces[k][i], w = mesh.faces[k][(i + 1) % 3];
          const auto e = edge(u, w);
          if (e == edge(a, b) || e == edge(b, c) || e == edge(c, a)) return true;
          return on_barrier[u] && on_barrier[w] &&
                 std::find(barriers.begin(), barriers.end(), e) != barriers.end();
        };
        if (!sides_meet(across, {left}, {right}, side, [&](int k, int i) { return !crosses(k, i); }))
          continue;
        // The right side at each vertex is its fan from `right` up to the cycle.
        std::vector<int> fan{right};
        side[right] = 1;
        for (std::size_t i = 0; i < fan.size(); ++i) {
          const int k = fan[i];
          for (int j = 0; j < 3; ++j) {
            const int g = across[k][j];
            if (g < 0 || side[g] || crosses(k, j)) continue;
            const auto& f = mesh.faces[g];
            if (std::none_of(f.begin(), f.end(), [&](int v) { return v == a || v == b || v == c; }))
              continue;
            side[g] = 1;
            fan.push_back(g);
          }
        }
        const bool two_sides = side[left] == 0;
        for (int k : fan) side[k] = 0;
        if (!two_sides) continue;
        for (int v : {a, b, c}) {
          on_barrier[v] = 1;
          for (int k : stars[v])
            for (int x : mesh.faces[k]) near_cut[x] = 1;
        }
        barriers.push_back(edge(a, b));
        barriers.push_back(edge(b, c));
        barriers.push_back(edge(c, a));
        cuts.push_back({{a, b, c}, std::move(fan)});
      }
    }
  }
  // The faces at a, b, c on the right take copies of them; a triangle closes each side.
  for (const Cut& cut : cuts) {
    const int n = static_cast<int>(mesh.vertices.size());
    for (int k : cut.right)
      for (int& v : mesh.faces[k])
        for (int j = 0; j < 3; ++j)
          if (v == cut.cycle[j]) v = n + j;
    for (int j = 0; j < 3; ++j) mesh.vertices.push_back(mesh.vertices[cut.cycle[j]]);
    mesh.faces.push_back({cut.cycle[0], cut.cycle[2], cut.cycle[1]});
    mesh.faces.push_back({n, n + 1, n + 2});
  }
  return static_cast<int>(cuts.size());
}

}  // namespace

CutHandles cut_unsupported_handles(TriangleMesh& mesh, const PointSet& samples,
                                   const HandleOptions& options) {
  if (!(options.support_degrees > 0 && options.support_degrees < 90) ||
      !(options.radius_spacings > 0) || options.band_rings < 1)
    throw std::invalid_argument(
        "cut_unsupported_handles: the angle must be in (0, 90), the radius > 0 and the rings >= 1");
  if (!options.enabled || mesh.faces.empty() || !samples.has_normals() || samples.size() < 2)
    return {};
  const detail::NearestNeighbors tree(samples.points);
  const double spacing = detail::average_spacing(samples.points, tree);
  const std::vector<char> unsupported =
      unsupported_faces(mesh, samples, tree, options.radius_spacings * spacing, options.support_degrees);
  detail::poll();
  const Adjacency adj(mesh);

  // A band of faces that is an annulus whose removal leaves the mesh in as
  // many pieces is a handle's waist.
  std::vector<char> removed(mesh.faces.size(), 0), in_band(mesh.faces.size(), 0),
      side(mesh.faces.size(), 0);
  std::map<int, char> loop_of;
  CutHandles report;
  // Grows `band` by the options' rings of faces; cuts it when it is a handle's waist.
  const auto try_cut = [&](std::vector<int> band) {
    for (int k : band) in_band[k] = 1;
    for (int ring = 0; ring < options.band_rings; ++ring) {
      const std::size_t n = band.size();
      for (std::size_t i = 0; i < n; ++i)
        for (int v : mesh.faces[band[i]])
          for (int g : adj.vertex_faces[v])
            if (!in_band[g]) {
              in_band[g] = 1;
              band.push_back(g);
            }
    }
    // A band that touches an earlier cut waits: between the two, a sliver could
    // be cut loose that the two loops' sides below do not see.
    const auto touches_cut = [&](int k) {
      for (int v : mesh.faces[k])
        for (int g : adj.vertex_faces[v])
          if (removed[g]) return true;
      return false;
    };
    bool cut = std::none_of(band.begin(), band.end(), touches_cut) &&
               is_annulus(mesh, adj, band, in_band, loop_of);
    if (cut) {  // the two loops' outer sides must stay one piece; otherwise it separates: a limb
      std::array<std::vector<int>, 2> outer;
      for (int k : band)
        for (int i = 0; i < 3; ++i) {
          const int g = adj.across[k][i];
          if (!in_band[g]) outer[loop_of.at(mesh.faces[k][i]) - 1].push_back(g);
        }
      cut = sides_meet(adj.across, outer[0], outer[1], side, [&](int k, int i) {
        const int g = adj.across[k][i];
        return !in_band[g] && !removed[g];
      });
    }
    for (int k : band) {
      in_band[k] = 0;
      if (cut) removed[k] = 1;
    }
    if (cut) {
      ++report.handles;
      report.faces += static_cast<int>(band.size());
    }
  };
  // The waists the samples contradict: clusters of unsupported faces, largest
  // first (ties by their first face), each grown into a band.
  std::vector<std::vector<int>> clusters = edge_connected(adj, unsupported);
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  for (const std::vector<int>& cluster : clusters) {
    detail::poll();
    try_cut(cluster);
  }
  if (report.handles > 0) {
    TriangleMesh capped = mesh;
    capped.attributes.clear();
    if (!cap_holes(capped, removed)) report = {};  // the filling failed: the mesh stays as it was
    else {
      capped.attributes = std::move(mesh.attributes);
      mesh = std::move(capped);
    }
  }
  return report;
}

int cut_triangle_waists(TriangleMesh& mesh) {
  int cuts = 0;
  for (bool deferred = true; deferred;) cuts += cut_triangle_waists_once(mesh, deferred);
  return cuts;
}

}  // namespace pdd
