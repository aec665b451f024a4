// Private to src/fem: per-tet geometry and the deterministic parallel
// assembly of vertex-by-vertex matrices.
//
// Assembly "pulls" instead of "pushing": each column j is computed by one
// task that walks the tets incident to vertex j in increasing order and adds
// their contributions. No two tasks write the same entry and every sum runs
// in an order fixed by the mesh, so the result does not depend on thread
// scheduling, and no triplet list (16 entries per tet) is ever stored.
#pragma once

#include <pdd/fem.h>

#include "common/cancellation.h"
#include "common/vertex_stars.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace pdd::detail {

// Geometry of one tet: its volume and the (constant) gradients of its four
// barycentric coordinates.
struct TetGradients {
  // Not zeroed: a vector of a million tets' is filled in parallel, and
  // zeroing it first took a serial second (value-initialization of an aggregate).
  TetGradients() {}
  double volume;
  Vec3 grad[4];
};

inline TetGradients tet_gradients(const TetMesh& mesh, int t) {
  const auto& tet = mesh.tets[t];
  const Vec3& x0 = mesh.vertices[tet[0]];
  const Vec3 e1 = mesh.vertices[tet[1]] - x0;
  const Vec3 e2 = mesh.vertices[tet[2]] - x0;
  const Vec3 e3 = mesh.vertices[tet[3]] - x0;
  const double det = e1.dot(e2.cross(e3));
  if (!(det > 0))
    throw std::invalid_argument("fem: tet " + std::to_string(t) +
                                " is not positively oriented (6 * volume = " +
                                std::to_string(det) + ")");
  TetGradients g;
  g.volume = det / 6.0;
  // Rows of [e1 e2 e3]^-1 are the gradients of barycentric coordinates 1..3.
  g.grad[1] = e2.cross(e3) / det;
  g.grad[2] = e3.cross(e1) / det;
  g.grad[3] = e1.cross(e2) / det;
  g.grad[0] = -(g.grad[1] + g.grad[2] + g.grad[3]);
  return g;
}

// tet_gradients of every tet, computed once, in parallel: the assemblies
// below visit each tet from the columns of its four corners.
inline std::vector<TetGradients> all_tet_gradients(const TetMesh& mesh) {
  std::vector<TetGradients> g(mesh.tets.size());
  polled_parallel_for(g.size(),
                      [&](std::size_t t) { g[t] = tet_gradients(mesh, static_cast<int>(t)); });
  return g;
}

// Eq. (11)'s contribution of tet t (gradients g) to column jl of the Hessian:
// out[9 i + 3a + b] = vol_t d_b(phi_i) d_a(phi_jl) for its local vertices i.
inline void hessian_column(const TetGradients& g, int jl, double* out) {
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) out[i * 9 + 3 * a + b] = g.volume * g.grad[i][b] * g.grad[jl][a];
}

// Assembles a (Blocks * |V|) x |V| matrix whose column j is
//   sum over tets t incident to j of contributions to rows b * |V| + v
//   (or v * Blocks + b when Interleaved),
// for every vertex v of t and block b < Blocks. `column(t, jl, out)` fills
// out[i * Blocks + b] with the contribution of tet t, local column jl, to
// local row i (vertex tet[i]) in block b.
// Position of (ring vertex k, block b) in a column of m ring vertices, rows sorted.
template <int Blocks, bool Interleaved>
inline int block_slot(int m, int k, int b) {
  return Interleaved ? k * Blocks + b : b * m + k;
}

// The values of column j (m ring vertices, `position` of each in the ring),
// summed over the tets around j in increasing order; `local` holds 4 * Blocks.
template <int Blocks, bool Interleaved, class ColumnFn>
void assemble_column(const TetMesh& mesh, const VertexStars& stars,
                     const std::vector<int>& position, int j, int m, ColumnFn& column,
                     double* local, double* vals) {
  std::fill(vals, vals + static_cast<std::ptrdiff_t>(Blocks) * m, 0.0);
  for (int s = stars.begin(j); s < stars.end(j); ++s) {
    const int t = stars.tets[s];
    const auto& tet = mesh.tets[t];
    column(t, local_index(tet, j), local);
    for (int i = 0; i < 4; ++i) {
      const int k = position[tet[i]];
      for (int b = 0; b < Blocks; ++b)
        vals[block_slot<Blocks, Interleaved>(m, k, b)] += local[i * Blocks + b];
    }
  }
}

template <int Blocks, bool Interleaved = false, class ColumnFn>
SparseMatrix assemble_by_columns(const TetMesh& mesh, const VertexStars& stars, ColumnFn column) {
  const int n = static_cast<int>(mesh.vertices.size());
  const OneRings rings = one_rings(mesh, stars);
  SparseMatrix A(static_cast<Eigen::Index>(Blocks) * n, n);
  std::vector<long long> start(n + 1, 0);
  for (int j = 0; j < n; ++j)
    start[j + 1] = start[j] +
                   static_cast<long long>(Blocks) * static_cast<long long>(rings[j].size());
  if (start[n] > std::numeric_limits<int>::max())
    throw std::length_error("fem: matrix has more non-zeros than an int index can hold");
  A.resizeNonZeros(static_cast<Eigen::Index>(start[n]));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  for (int j = 0; j <= n; ++j) outer[j] = static_cast<int>(start[j]);
  // Per thread, the position of each vertex in the current column's ring.
  PerThreadTable positions = per_thread_table(n);
  polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    double local[4 * Blocks];
    std::vector<int>& position = positions.local();
    for (int j = r.begin(); j < r.end(); ++j) {
      const Ring ring = rings[j];
      const int m = static_cast<int>(ring.size());
      for (int k = 0; k < m; ++k) position[ring[k]] = k;
      int* rows = inner + start[j];
      for (int b = 0; b < Blocks; ++b)
        for (int k = 0; k < m; ++k)
          rows[block_slot<Blocks, Interleaved>(m, k, b)] =
              Interleaved ? ring[k] * Blocks + b : b * n + ring[k];
      assemble_column<Blocks, Interleaved>(mesh, stars, position, j, m, column, local,
                                           values + start[j]);
    }
  });
  return A;
}

// The Hessian of Eq. (11) with its rows either as documented in fem.h
// ((3a + b) |V| + v) or interleaved (9 v + 3a + b), operators.cpp.
SparseMatrix hessian_matrix_rows(const TetMesh& mesh, bool interleaved);

}  // namespace pdd::detail
