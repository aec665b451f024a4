// The piecewise-linear operators of §3.5: volumes, masses, G, L (Eq. (12)),
// G^T W G and the Hessian H (Eq. (11)).
#include <pdd/fem.h>

#include "fem/assembly.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace pdd {

using detail::tet_gradients;
using detail::TetGradients;

Eigen::VectorXd tet_volumes(const TetMesh& mesh) {
  const int nt = static_cast<int>(mesh.tets.size());
  Eigen::VectorXd vol(nt);
  detail::polled_parallel_for(nt, [&](int t) { vol[t] = tet_gradients(mesh, t).volume; });
  return vol;
}

Eigen::VectorXd vertex_masses(const TetMesh& mesh) {
  const Eigen::VectorXd vol = tet_volumes(mesh);
  const detail::VertexStars stars = detail::vertex_stars(mesh);
  const int n = static_cast<int>(mesh.vertices.size());
  Eigen::VectorXd mass(n);
  detail::polled_parallel_for(n, [&](int v) {
    double m = 0;
    for (int s = stars.begin(v); s < stars.end(v); ++s) m += vol[stars.tets[s]];
    mass[v] = m / 4.0;
  });
  return mass;
}

Eigen::VectorXd gradient_transpose_times(const TetMesh& mesh, const std::vector<Vec3>& per_tet) {
  if (per_tet.size() != mesh.tets.size())
    throw std::invalid_argument("gradient_transpose_times: one vector per tet is required");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.vertices.size()));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (per_tet[t].isZero(0)) continue;
    const TetGradients g = detail::tet_gradients(mesh, static_cast<int>(t));
    for (int i = 0; i < 4; ++i) out[mesh.tets[t][i]] += g.grad[i].dot(per_tet[t]);
    detail::poll_every(t);  // the run's cancellation
  }
  return out;
}

SparseMatrix gradient_matrix(const TetMesh& mesh) {
  // Column v holds rows 3t..3t+2 for every tet t around v, already sorted
  // because stars list tets in increasing order: the compressed arrays are
  // written directly.
  const detail::VertexStars stars = detail::vertex_stars(mesh);
  const std::vector<TetGradients> gradients = detail::all_tet_gradients(mesh);
  const int n = static_cast<int>(mesh.vertices.size());
  SparseMatrix G(3 * static_cast<Eigen::Index>(mesh.tets.size()), n);
  G.resizeNonZeros(3 * static_cast<Eigen::Index>(stars.tets.size()));
  for (int v = 0; v <= n; ++v) G.outerIndexPtr()[v] = 3 * stars.offsets[v];
  tbb::parallel_for(0, n, [&](int v) {
    for (int s = stars.begin(v); s < stars.end(v); ++s) {
      const int t = stars.tets[s];
      const Vec3& grad = gradients[t].grad[detail::local_index(mesh.tets[t], v)];
      for (int k = 0; k < 3; ++k) {
        G.innerIndexPtr()[3 * s + k] = 3 * t + k;
        G.valuePtr()[3 * s + k] = grad[k];
      }
    }
  });
  return G;
}

// Eq. (12), computed from edge lengths and dihedral angles (not from G, so
// that the identity L = G^T M_T G is a real check of both).
SparseMatrix cotangent_laplacian(const TetMesh& mesh) {
  const detail::VertexStars stars = detail::vertex_stars(mesh);
  return detail::assemble_by_columns<1>(mesh, stars, [&](int t, int jl, double* out) {
    const auto& tet = mesh.tets[t];
    Vec3 x[4];
    for (int i = 0; i < 4; ++i) x[i] = mesh.vertices[tet[i]];
    // Outward area normals of the faces opposite each vertex.
    Vec3 face_normal[4];
    for (int i = 0; i < 4; ++i) {
      const Vec3& a = x[(i + 1) % 4];
      const Vec3& b = x[(i + 2) % 4];
      const Vec3& c = x[(i + 3) % 4];
      Vec3 nrm = (b - a).cross(c - a);
      if (nrm.dot(x[i] - a) > 0) nrm = -nrm;
      face_normal[i] = nrm.normalized();
    }
    double diagonal = 0;
    for (int i = 0; i < 4; ++i) {
      if (i == jl) continue;
      // (k, l): the edge opposite (i, jl); the faces meeting at it are those
      // opposite i and opposite jl.
      int kl[2], c = 0;
      for (int m = 0; m < 4; ++m)
        if (m != i && m != jl) kl[c++] = m;
      const double length = (x[kl[0]] - x[kl[1]]).norm();
      const double cos_theta = -face_normal[i].dot(face_normal[jl]);
      const double sin_theta = face_normal[i].cross(face_normal[jl]).norm();
      out[i] = -length * (cos_theta / sin_theta) / 6.0;
      diagonal -= out[i];
    }
    out[jl] = diagonal;
  });
}

namespace {

// G^T W G with w_j = weighted(t, grad phi_j) the metric of tet t applied to a
// gradient. Each tet's gradients are computed where used (four times) rather
// than stored: 100 bytes per tet, over 1 GB at a million vertices.
template <class Weighted>
SparseMatrix stiffness_of(const TetMesh& mesh, Weighted weighted) {
  const detail::VertexStars stars = detail::vertex_stars(mesh);
  return detail::assemble_by_columns<1>(mesh, stars, [&](int t, int jl, double* out) {
    const TetGradients g = detail::tet_gradients(mesh, t);
    const Vec3 wj = weighted(t, g.grad[jl]);
    for (int i = 0; i < 4; ++i) out[i] = g.grad[i].dot(wj);
  });
}

}  // namespace

SparseMatrix weighted_stiffness(const TetMesh& mesh, const std::vector<Eigen::Matrix3d>& weights) {
  if (weights.size() != mesh.tets.size())
    throw std::invalid_argument("weighted_stiffness: one 3x3 weight per tet is required");
  return stiffness_of(mesh, [&](int t, const Vec3& grad) -> Vec3 { return weights[t] * grad; });
}

SparseMatrix weighted_stiffness(const TetMesh& mesh, const std::vector<double>& weights) {
  if (weights.size() != mesh.tets.size())
    throw std::invalid_argument("weighted_stiffness: one weight per tet is required");
  return stiffness_of(mesh, [&](int t, const Vec3& grad) -> Vec3 { return weights[t] * grad; });
}

// Eq. (11): (H f)_v,ab = sum_t vol_t d_b(phi_v) d_a(f), i.e. column w holds
// vol_t d_b(phi_v) d_a(phi_w) at row (3a + b) |V| + v.
namespace detail {

SparseMatrix hessian_matrix_rows(const TetMesh& mesh, bool interleaved) {
  const VertexStars stars = vertex_stars(mesh);
  const std::vector<TetGradients> gradients = all_tet_gradients(mesh);
  const auto column = [&](int t, int jl, double* out) { hessian_column(gradients[t], jl, out); };
  if (interleaved) return assemble_by_columns<9, true>(mesh, stars, column);
  return assemble_by_columns<9>(mesh, stars, column);
}

}  // namespace detail

SparseMatrix hessian_matrix(const TetMesh& mesh) { return detail::hessian_matrix_rows(mesh, false); }

}  // namespace pdd
