// Topology of a triangle mesh: manifoldness, boundary, components, Euler
// characteristic and genus. Hand-written on sorted index arrays: a
// CGAL::Surface_mesh cannot even be built from a non-manifold face set, which
// is exactly what this check must report on.
#include <pdd/quality.h>

#include <algorithm>
#include <numeric>
#include <tuple>

#include "metrics/elements.h"

namespace pdd {
namespace {

// Union-find with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t(0));
  }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::size_t> parent_;
};

// One side of an edge: the face, its corners at the edge's lower and higher
// vertex, and whether the face runs the edge from lower to higher.
struct HalfEdge {
  int lo, hi;
  std::size_t face;
  int corner_lo, corner_hi;
  bool forward;
};

}  // namespace

SurfaceTopology surface_topology(const TriangleMesh& mesh) {
  detail::check_indices(mesh.faces, mesh.vertices.size(), "face");
  SurfaceTopology s;
  s.faces = mesh.faces.size();

  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * s.faces);
  std::vector<char> referenced(mesh.vertices.size(), 0);
  DisjointSets vertex_sets(mesh.vertices.size());
  for (std::size_t i = 0; i < s.faces; ++i) {
    const auto& f = mesh.faces[i];
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) ++s.degenerate_faces;
    for (int k = 0; k < 3; ++k) {
      const int u = f[k], v = f[(k + 1) % 3];
      referenced[u] = 1;
      vertex_sets.join(u, v);
      if (u == v) continue;
      half_edges.push_back(u < v ? HalfEdge{u, v, i, k, (k + 1) % 3, true}
                                 : HalfEdge{v, u, i, (k + 1) % 3, k, false});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return std::tie(a.lo, a.hi, a.face) < std::tie(b.lo, b.hi, b.face);
  });

  // Corners (3 * face + k) around a vertex are joined across every edge with
  // exactly two faces; the sets left at a vertex are its fans.
  DisjointSets corner_sets(3 * s.faces);
  for (std::size_t begin = 0; begin < half_edges.size();) {
    std::size_t end = begin + 1;
    while (end < half_edges.size() && half_edges[end].lo == half_edges[begin].lo &&
           half_edges[end].hi == half_edges[begin].hi)
      ++end;
    ++s.edges;
    const std::size_t count = end - begin;
    if (count == 1) ++s.boundary_edges;
    if (count > 2) ++s.non_manifold_edges;
    if (count == 2) {
      const HalfEdge &a = half_edges[begin], &b = half_edges[begin + 1];
      if (a.forward == b.forward) ++s.inconsistent_edges;
      corner_sets.join(3 * a.face + a.corner_lo, 3 * b.face + b.corner_lo);
      corner_sets.join(3 * a.face + a.corner_hi, 3 * b.face + b.corner_hi);
    }
    begin = end;
  }

  std::vector<std::pair<int, std::size_t>> fans;  // (vertex, fan)
  fans.reserve(3 * s.faces);
  for (std::size_t i = 0; i < s.faces; ++i)
    for (int k = 0; k < 3; ++k) fans.emplace_back(mesh.faces[i][k], corner_sets.find(3 * i + k));
  std::sort(fans.begin(), fans.end());
  fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
  for (std::size_t i = 1; i < fans.size(); ++i)
    if (fans[i].first == fans[i - 1].first && (i < 2 || fans[i - 2].first != fans[i].first))
      ++s.non_manifold_vertices;

  for (std::size_t v = 0; v < referenced.size(); ++v) {
    if (!referenced[v]) continue;
    ++s.vertices;
    if (vertex_sets.find(v) == v) ++s.components;
  }
  s.euler_characteristic =
      static_cast<long>(s.vertices) - static_cast<long>(s.edges) + static_cast<long>(s.faces);
  s.edge_manifold =
      s.non_manifold_edges == 0 && s.inconsistent_edges == 0 && s.degenerate_faces == 0;
  s.manifold = s.edge_manifold && s.non_manifold_vertices == 0;
  s.closed = s.faces > 0 && s.boundary_edges == 0;
  if (s.closed && s.manifold)
    s.genus = (2 * static_cast<long>(s.components) - s.euler_characteristic) / 2;
  return s;
}

}  // namespace pdd
