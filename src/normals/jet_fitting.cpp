// Quadratic jets fitted to each point's neighbourhood (CGAL's Jet_fitting_3):
// the normals, the projected points and the neighbourhoods' planes of
// normals.h. One fit gives all three, so noisy inputs, which need the first
// two, pay for one (CGAL's jet_estimate_normals and jet_smooth_point_set each
// fit the same jets again), and the planes cost no second neighbour query.
#include <pdd/errors.h>
#include <pdd/normals.h>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"

#include <CGAL/Eigen_svd.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pdd {
namespace {

template <class Point>
LocalPlane fit_plane(const std::vector<Point>& neighbourhood) {
  const double count = static_cast<double>(neighbourhood.size());
  Vec3 centre = Vec3::Zero();
  for (const Point& p : neighbourhood) centre += Vec3(p.x(), p.y(), p.z());
  centre /= count;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Point& p : neighbourhood) {
    const Vec3 d = Vec3(p.x(), p.y(), p.z()) - centre;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance / count);
  const Eigen::Vector3d values = solver.eigenvalues().cwiseMax(0.0);  // ascending
  const double sum = values.sum();
  return {centre, solver.eigenvectors().col(0), std::sqrt(values[0]),
          sum > 0 ? values[0] / sum : 0.0};
}

}  // namespace

int noise_scaled_neighbors(double noise, double spacing, int neighbors) {
  if (!(spacing > 0) || !(noise > 0)) return neighbors;
  const double ratio = noise / (0.25 * spacing);
  const double grown = neighbors * ratio * ratio;
  return grown > neighbors ? static_cast<int>(std::min<double>(std::lround(grown), kMaxNoiseNeighbors))
                           : neighbors;
}

JetFits fit_jets(const std::vector<Vec3>& points, int neighbors, const std::string& source) {
  if (points.size() < kMinPointsForNormals)
    throw InputError(source + ": " + std::to_string(points.size()) +
                     " points are too few to estimate normals from (at least " +
                     std::to_string(kMinPointsForNormals) + " are needed)");
  using Kernel = CGAL::Simple_cartesian<double>;
  using Fitting = CGAL::Monge_via_jet_fitting<Kernel, Kernel, CGAL::Eigen_svd>;
  constexpr int kDegree = 2;  // a quadric, as CGAL's defaults
  constexpr int kFewest = (kDegree + 1) * (kDegree + 2) / 2;
  const int k = std::clamp(neighbors, kFewest, static_cast<int>(points.size()) - 1);
  const detail::NearestNeighbors tree(points);
  const std::vector<int>& order = tree.spatial_order();  // queries in cache order
  JetFits fits;
  fits.points.resize(points.size());
  fits.normals.resize(points.size());
  fits.planes.resize(points.size());
  detail::polled_parallel_ranges(points.size(), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<Kernel::Point_3> neighbourhood;
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const int i = order[s];
      neighbourhood.clear();
      for (int j : tree.query(points[i], k + 1))  // the point and k others
        neighbourhood.emplace_back(points[j].x(), points[j].y(), points[j].z());
      Fitting fitting;
      // Monge degree 1: the origin and the normal, no curvatures.
      const Fitting::Monge_form form =
          fitting(neighbourhood.begin(), neighbourhood.end(), kDegree, 1);
      const Kernel::Point_3 o = form.origin();
      const Kernel::Vector_3 n = form.normal_direction();
      fits.points[i] = Vec3(o.x(), o.y(), o.z());
      fits.planes[i] = fit_plane(neighbourhood);
      fits.normals[i] = Vec3(n.x(), n.y(), n.z());
    }
  });
  for (std::size_t i = 0; i < points.size(); ++i) {
    // A neighbourhood that is a line or a point gives no plane: say so rather
    // than hand on a zero or NaN normal.
    Vec3& n = fits.normals[i];
    const double length = n.norm();
    if (!(length > 0) || !std::isfinite(length) || !fits.points[i].allFinite())
      throw InputError(source + ": the neighbourhood of point " + std::to_string(i + 1) +
                       " is too flat or too degenerate to estimate a normal from");
    n /= length;
  }
  return fits;
}

std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbors,
                                   const std::string& source) {
  return fit_jets(points, neighbors, source).normals;
}

}  // namespace pdd
