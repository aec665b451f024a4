// Marching tetrahedra with shared isovertices, shortest-diagonal quad splits
// and outward orientation (§2.1, §3.4). Hand-written: CGAL has no marching
// tetrahedra on a user triangulation, and the optimizer and refiner need the
// facet -> tet and isovertex -> edge maps this produces.
//
// The scan is serial on purpose: isovertex numbering follows the order of
// first appearance, which a parallel scan would have to reconstruct, and the
// scan is linear and cheap next to the solve that precedes it.
#include <pdd/contour.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "common/cancellation.h"

namespace pdd {
namespace {

// Builds the isosurface tet by tet; isovertices are keyed by their edge.
class Contourer {
 public:
  Contourer(const TetMesh& mesh, const std::vector<double>& f, double isovalue)
      : mesh_(mesh), f_(f), isovalue_(isovalue) {}

  IsoSurface run() {
    for (std::size_t t = 0; t < mesh_.tets.size(); ++t) {
      contour_tet(static_cast<int>(t));
      detail::poll_every(t);  // the run's cancellation
    }
    return std::move(out_);
  }

 private:
  // Symbolic perturbation: a value equal to the isovalue counts as positive.
  bool negative(int v) const { return f_[v] < isovalue_; }

  // The isovertex on edge (a, b), a negative and b positive; created on first use.
  int isovertex(int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    const std::uint64_t key =
        (static_cast<std::uint64_t>(lo) << 32) | static_cast<std::uint32_t>(hi);
    const auto [it, inserted] =
        index_.try_emplace(key, static_cast<int>(out_.mesh.vertices.size()));
    if (inserted) {
      // f(a) < isovalue <= f(b), so 0 < t <= 1; (1 - t) a + t b is exactly b at t = 1.
      const double t = (isovalue_ - f_[a]) / (f_[b] - f_[a]);
      out_.mesh.vertices.push_back((1.0 - t) * mesh_.vertices[a] + t * mesh_.vertices[b]);
      out_.vertex_edge.push_back({lo, hi});
    }
    return it->second;
  }

  void add_triangle(int t, int a, int b, int c) {
    out_.mesh.faces.push_back({a, b, c});
    out_.facet_tet.push_back(t);
  }

  void contour_tet(int t) {
    const std::array<int, 4>& tet = mesh_.tets[t];
    // The tet's corners reordered negatives first (stably); `odd` is the
    // parity of that permutation. The reordered tet is positively oriented
    // when the permutation is even.
    int v[4];
    int count = 0;
    for (int i = 0; i < 4; ++i)
      if (negative(tet[i])) v[count++] = i;
    const int negatives = count;
    if (negatives == 0 || negatives == 4) return;
    for (int i = 0; i < 4; ++i)
      if (!negative(tet[i])) v[count++] = i;
    bool odd = false;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (v[i] > v[j]) odd = !odd;
    for (int& i : v) i = tet[i];

    // For a positively oriented (n0, p1, p2, p3), the triangle on edges
    // n0p1, n0p2, n0p3 faces away from n0; for (n0, n1, n2, p3) the triangle
    // on n0p3, n1p3, n2p3 faces towards p3; for (n0, n1, p2, p3) the cycle
    // n0p2, n0p3, n1p3, n1p2 faces from n0n1 to p2p3. Odd permutations flip.
    if (negatives == 1 || negatives == 3) {
      int corner[3];
      for (int i = 0; i < 3; ++i)
        corner[i] = negatives == 1 ? isovertex(v[0], v[i + 1]) : isovertex(v[i], v[3]);
      if (odd) std::swap(corner[1], corner[2]);
      add_triangle(t, corner[0], corner[1], corner[2]);
      return;
    }
    int q[4] = {isovertex(v[0], v[2]), isovertex(v[0], v[3]), isovertex(v[1], v[3]),
                isovertex(v[1], v[2])};
    if (odd) std::swap(q[1], q[3]);
    // §3.4: split the quadrangle along its shortest diagonal.
    const std::vector<Vec3>& p = out_.mesh.vertices;
    if ((p[q[0]] - p[q[2]]).squaredNorm() <= (p[q[1]] - p[q[3]]).squaredNorm()) {
      add_triangle(t, q[0], q[1], q[2]);
      add_triangle(t, q[0], q[2], q[3]);
    } else {
      add_triangle(t, q[0], q[1], q[3]);
      add_triangle(t, q[1], q[2], q[3]);
    }
  }

  const TetMesh& mesh_;
  const std::vector<double>& f_;
  const double isovalue_;
  IsoSurface out_;
  std::unordered_map<std::uint64_t, int> index_;  // edge (lo, hi) -> isovertex
};

}  // namespace

IsoSurface marching_tetrahedra(const TetMesh& mesh, const std::vector<double>& f, double isovalue) {
  if (f.size() != mesh.vertices.size())
    throw std::invalid_argument("marching_tetrahedra: " + std::to_string(f.size()) +
                                " values for " + std::to_string(mesh.vertices.size()) +
                                " vertices");
  for (std::size_t i = 0; i < f.size(); ++i)
    if (!std::isfinite(f[i]))
      throw std::invalid_argument("marching_tetrahedra: f at vertex " + std::to_string(i) +
                                  " is not finite");
  if (!std::isfinite(isovalue))
    throw std::invalid_argument("marching_tetrahedra: the isovalue is not finite");
  return Contourer(mesh, f, isovalue).run();
}

}  // namespace pdd
