#include "solvers/normal_field.h"

#include "common/nearest_neighbors.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

namespace pdd::detail {

double mean_spacing(const std::vector<Vec3>& points) {
  if (points.size() < 2) return 0;
  const NearestNeighbors nn(points);
  const int n = static_cast<int>(points.size());
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<int>(0, n), 0.0,
      [&](const tbb::blocked_range<int>& r, double s) {
        for (int i = r.begin(); i < r.end(); ++i) {
          const std::vector<int> k = nn.query(points[i], 2);
          const int other = k[0] == i ? k[1] : k[0];
          s += (points[other] - points[i]).norm();
        }
        return s;
      },
      std::plus<double>());
  return sum / n;
}

std::vector<Vec3> smoothed_normal_field(const TetMesh& mesh, const std::vector<Vec3>& points,
                                        const std::vector<Vec3>& normals, double sigma) {
  const NearestNeighbors samples(points);  // read-only queries, safe in parallel

  const int nt = static_cast<int>(mesh.tets.size());
  std::vector<Vec3> field(nt, Vec3::Zero());
  tbb::parallel_for(tbb::blocked_range<int>(0, nt), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t < r.end(); ++t) {
      Vec3 x[4];
      for (int i = 0; i < 4; ++i) x[i] = mesh.vertices[mesh.tets[t][i]];
      const Vec3 c = (x[0] + x[1] + x[2] + x[3]) / 4.0;
      double spread = 0;
      for (int i = 0; i < 4; ++i) spread += (x[i] - c).squaredNorm();
      const double variance = sigma * sigma + spread / 60.0;  // per axis
      // The tree and the query fix the order of the points found, so the
      // sum is deterministic.
      const std::vector<int> found = samples.within(c, 3.0 * std::sqrt(variance));
      const double scale = std::pow(2.0 * M_PI * variance, -1.5);
      Vec3 sum = Vec3::Zero();
      for (int p : found)
        sum += std::exp(-(points[p] - c).squaredNorm() / (2.0 * variance)) * normals[p];
      field[t] = scale * sum;
    }
  });
  return field;
}

}  // namespace pdd::detail
