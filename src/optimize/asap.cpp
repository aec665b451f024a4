// The as-similar-as-possible (ASAP) term of §3.3, Eqs. (2)-(7): each tet is
// pulled towards the similar copy of the regular tetrahedron that fits it
// best, scaled to its smoothed volume.
#include "optimize/energy_terms.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <memory>

namespace pdd::optimize_detail {
namespace {

// t': the centered regular tetrahedron with unit edges, positively oriented
// like every tet of the domain, (v1 - v0) . ((v2 - v0) x (v3 - v0)) > 0, so
// that corner i of t' is matched to corner i of t by a rotation.
const std::array<Vec3, 4>& reference_tet() {
  static const std::array<Vec3, 4> t = [] {
    const double s = 1.0 / (2.0 * std::sqrt(2.0));
    return std::array<Vec3, 4>{Vec3(s, s, s), Vec3(-s, s, -s), Vec3(s, -s, -s), Vec3(-s, -s, s)};
  }();
  return t;
}
const double kReferenceVolume = 1.0 / (6.0 * std::sqrt(2.0));  // vol(t')

double signed_volume(const std::array<Vec3, 4>& v) {
  return (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) / 6.0;
}

// The rotation V U^T of Eqs. (4) and (6) for C = U Sigma V^T, with a
// reflection fixed by flipping the pair of the smallest singular value.
// From the eigenvectors of C^T C = V Sigma^2 V^T (closed form, 4x faster
// than a Jacobi SVD): u_i = C v_i / sigma_i for the two largest, the third
// pair completing both frames to rotations. C of rank <= 1 (a tet with all
// corners on a line) goes through the SVD.
Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& C) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(C.transpose() * C);
  const Eigen::Vector3d& sigma2 = eigen.eigenvalues();  // ascending
  if (!(sigma2[1] > 1e-12 * sigma2[2])) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU();
    const Eigen::Matrix3d& V = svd.matrixV();
    if ((V * U.transpose()).determinant() < 0) U.col(2) = -U.col(2);
    return V * U.transpose();
  }
  const Vec3 v1 = eigen.eigenvectors().col(2), v2 = eigen.eigenvectors().col(1);
  const Vec3 u1 = (C * v1).normalized();
  Vec3 u2 = C * v2;
  u2 = (u2 - u2.dot(u1) * u1).normalized();
  return v1 * u1.transpose() + v2 * u2.transpose() + v1.cross(v2) * u1.cross(u2).transpose();
}

// S* of Eq. (7) for a tet whose smoothed volume is `smoothed_volume`: the
// target of its centered corner i, c(t) + S* v_{t'_i} - c(t), is S* v_{t'_i}.
// S* = s R, kept as the quaternion of R times sqrt(s) (32 bytes against 72:
// with the tets' volumes, the largest array of the optimizer's round).
struct Similarity {
  Eigen::Quaterniond q;
  // s R from q (|q|^2 = s): the rotation's homogeneous form.
  Eigen::Matrix3d matrix() const {
    const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
    Eigen::Matrix3d m;
    m << w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
        2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
        2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z;
    return m;
  }
};

Similarity asap_similarity(const std::array<Vec3, 4>& v, double smoothed_volume) {
  const auto& ref = reference_tet();
  const Vec3 center = 0.25 * (v[0] + v[1] + v[2] + v[3]);
  // Eq. (3): C = t' (t - c(t))^T, summed over the corners.
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) C += ref[i] * (v[i] - center).transpose();
  // Eq. (5): Sigma' = cbrt(vol_bar(t) / vol(t')) I_3.
  const double scale = std::cbrt(std::max(smoothed_volume, 0.0) / kReferenceVolume);
  Eigen::Quaterniond q(best_rotation(C));
  q.coeffs() *= std::sqrt(scale) / q.norm();
  return {q};
}

}  // namespace

void add_asap_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q) {
  const auto& tets = domain.tets();
  const auto& neighbors = domain.tet_neighbors();
  const auto& x = domain.vertices();
  const std::size_t m = tets.size();
  auto corners = [&](std::size_t t) {
    return std::array<Vec3, 4>{x[tets[t][0]], x[tets[t][1]], x[tets[t][2]], x[tets[t][3]]};
  };

  std::vector<double> volume(m);
  detail::polled_parallel_for(m, [&](std::size_t t) { volume[t] = signed_volume(corners(t)); });

  // vol_bar(t): the mean of the volumes of t and of the tets adjacent to it.
  // Each tet keeps S* (32 bytes; its four targets took 96, the peak of a 1M
  // run). new[] leaves them unzeroed (a vector would zero a GB serially).
  const std::unique_ptr<Similarity[]> similarity(new Similarity[m]);
  detail::polled_parallel_for(m, [&](std::size_t t) {
    double sum = volume[t];
    int count = 1;
    for (int nb : neighbors[t])
      if (nb >= 0) {
        sum += volume[nb];
        ++count;
      }
    similarity[t] = asap_similarity(corners(t), sum / count);
  });

  // w_a(t) E_a(t) with E_a(t) = sum_i |(v_i - c(t)) - S* v_{t'_i}|^2 (Eq. (7)):
  // per coordinate, x^T P x - 2 q^T x + |q|^2 with P = I_4 - 1/4 (the
  // centering, P q = q since the targets are centered). Zero-volume tets
  // have zero weight. The volumes become the weights in place.
  std::vector<double>& weight = volume;
  for (std::size_t t = 0; t < m; ++t) weight[t] = weight_scale * std::abs(volume[t]);
  const auto& ref = reference_tet();
  const detail::VertexStars& stars = q.stars();
  q.add_isotropic_by_columns([&](int j, auto add) {
    for (int s = stars.begin(j); s < stars.end(j); ++s) {
      const int t = stars.tets[s];
      const int jl = detail::local_index(tets[t], j);
      for (int i = 0; i < 4; ++i) add(tets[t][i], weight[t] * ((i == jl) - 0.25));
      q.b.segment<3>(3 * j) += weight[t] * (similarity[t].matrix() * ref[jl]);
    }
  });
  for (std::size_t t = 0; t < m; ++t) {
    const Eigen::Matrix3d S = similarity[t].matrix();
    for (int i = 0; i < 4; ++i) q.c += weight[t] * (S * ref[i]).squaredNorm();
    detail::poll_every(t);
  }
}

}  // namespace pdd::optimize_detail
