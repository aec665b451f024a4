#include "solvers/normal_field.h"

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <numeric>
#include <cmath>

namespace pdd::detail {

double mean_spacing(const std::vector<Vec3>& points, const NearestNeighbors& nn) {
  if (points.size() < 2) return 0;
  const int n = static_cast<int>(points.size());
  // Each distance in its own slot, summed in order: a parallel reduction's
  // order, and so its rounding, would follow the threads' timing.
  std::vector<double> distance(n);
  polled_parallel_for(n, [&](int s) {
    const int i = nn.spatial_order()[s];  // the tree's order: cached paths
    const std::vector<int> k = nn.query(points[i], 2);
    distance[i] = (points[k[0] == i ? k[1] : k[0]] - points[i]).norm();
  });
  return std::accumulate(distance.begin(), distance.end(), 0.0) / n;
}

std::vector<double> density_weights(const std::vector<Vec3>& points, const NearestNeighbors& tree,
                                    double sigma) {
  const int n = static_cast<int>(points.size());
  std::vector<double> density(n, 0.0);
  polled_parallel_for(n, [&](int s) {
    const int i = tree.spatial_order()[s];  // the tree's order: cached paths
    double sum = 0;                          // at least 1: the sample itself
    for (int q : tree.within(points[i], 3.0 * sigma))
      sum += std::exp(-(points[q] - points[i]).squaredNorm() / (2.0 * sigma * sigma));
    density[i] = sum;
  });
  double mean = 0;
  for (double d : density) mean += d;
  mean /= n;
  std::vector<double> weight(n);
  for (int i = 0; i < n; ++i) weight[i] = mean / density[i];
  return weight;
}

std::vector<Vec3> smoothed_normal_field(const TetMesh& mesh, const std::vector<Vec3>& points,
                                        const NearestNeighbors& samples,
                                        const std::vector<Vec3>& normals, double sigma) {

  const int nt = static_cast<int>(mesh.tets.size());
  std::vector<Vec3> field(nt, Vec3::Zero());
  tbb::parallel_for(tbb::blocked_range<int>(0, nt), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t < r.end(); ++t) {
      Vec3 x[4];
      for (int i = 0; i < 4; ++i) x[i] = mesh.vertices[mesh.tets[t][i]];
      const Vec3 c = (x[0] + x[1] + x[2] + x[3]) / 4.0;
      double spread = 0, reach = 0;
      for (int i = 0; i < 4; ++i) {
        spread += (x[i] - c).squaredNorm();
        reach = std::max(reach, (x[i] - c).norm());
      }
      // A tet no larger than the kernel: its four-point rule (exact for
      // quadratics), each point's Gaussian widened by the variance of a
      // quarter of the tet, so that a kernel as narrow as the tets is sampled
      // and not just read at the centroid. A larger tet: one Gaussian at the
      // centroid widened by the tet's whole variance.
      const bool four = spread / 60.0 <= sigma * sigma;
      const double variance = sigma * sigma + spread / (four ? 240.0 : 60.0);  // per axis
      constexpr double a = 0.5854101966249685, b = 0.1381966011250105;
      Vec3 q[4] = {c, c, c, c};
      if (four)
        for (int i = 0; i < 4; ++i) q[i] = c + (a - b) * (x[i] - c);
      // The tree and the query fix the order of the points found, so the
      // sum is deterministic.
      const std::vector<int> found =
          samples.within(c, 3.0 * std::sqrt(variance) + (four ? (a - b) * reach : 0.0));
      const int rule = four ? 4 : 1;
      const double scale = std::pow(2.0 * M_PI * variance, -1.5) / rule;
      Vec3 sum = Vec3::Zero();
      for (int p : found)
        for (int i = 0; i < rule; ++i)
          sum += std::exp(-(points[p] - q[i]).squaredNorm() / (2.0 * variance)) * normals[p];
      field[t] = scale * sum;
    }
  });
  return field;
}

}  // namespace pdd::detail
