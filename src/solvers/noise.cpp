// The input's noise level and the value weights of SSD and the spectral solver chosen from it.
#include <pdd/errors.h>
#include <pdd/solvers.h>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"
#include "common/statistics_sample.h"

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pdd {

namespace {

// The residual of one point's neighbourhood: RMS distance of the neighbours
// to the cubic height field h(u, v) fitted to them in their principal frame,
// over the degrees of freedom left (k - 10).
double cubic_fit_residual(const std::vector<Vec3>& points, const std::vector<int>& neighbours) {
  const int k = static_cast<int>(neighbours.size());
  Vec3 centroid = Vec3::Zero();
  for (int j : neighbours) centroid += points[j];
  centroid /= k;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int j : neighbours) covariance += (points[j] - centroid) * (points[j] - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> frame(covariance);
  const Vec3 n = frame.eigenvectors().col(0);
  const Vec3 u = frame.eigenvectors().col(2);
  const Vec3 v = frame.eigenvectors().col(1);
  Eigen::MatrixXd A(k, 10);
  Eigen::VectorXd h(k);
  for (int t = 0; t < k; ++t) {
    const Vec3 d = points[neighbours[t]] - centroid;
    const double x = d.dot(u), y = d.dot(v);
    A.row(t) << x * x * x, x * x * y, x * y * y, y * y * y, x * x, x * y, y * y, x, y, 1;
    h[t] = d.dot(n);
  }
  const Eigen::VectorXd coefficients = A.colPivHouseholderQr().solve(h);
  return std::sqrt((A * coefficients - h).squaredNorm() / (k - 10));
}

}  // namespace

double estimate_noise(const PointSet& points, int neighbors) {
  if (neighbors < 11)
    throw InputError("noise estimate: a cubic fit needs at least 11 neighbours, got " +
                     std::to_string(neighbors));
  if (static_cast<int>(points.size()) < neighbors) return 0;
  const detail::NearestNeighbors knn(points.points);
  const std::size_t stride = detail::statistics_stride(points.size());
  std::vector<double> residual((points.size() + stride - 1) / stride);
  detail::polled_parallel_for(residual.size(), [&](std::size_t i) {
    const Vec3& p = points.points[i * stride];
    residual[i] = cubic_fit_residual(points.points, knn.query(p, neighbors));
  });
  const auto quartile = residual.begin() + residual.size() / 4;
  std::nth_element(residual.begin(), quartile, residual.end());
  return *quartile;
}

double ssd_value_weight(double noise, double length) {
  const double sigma = noise / length;
  return std::min(kSsdValueWeightNoiseScale / (sigma * sigma), kSsdMaxValueWeight);
}

double spectral_value_weight(double noise, double spacing, double length) {
  const auto [r0, r1] = kSpectralSmoothedNoise;
  const double ramp = spacing > 0 ? std::clamp((noise / spacing - r0) / (r1 - r0), 0.0, 1.0) : 0;
  const double s = std::max(noise, kSpectralSmoothingSpacings * spacing * ramp) / length;
  return std::min(kSpectralValueWeightNoiseScale / (s * s * s), kSpectralMaxValueWeight);
}

}  // namespace pdd
