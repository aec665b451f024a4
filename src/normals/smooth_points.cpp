// Points projected onto their neighbourhood's jet (CGAL Point_set_processing_3).
#include <pdd/normals.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/jet_smooth_point_set.h>

#include <algorithm>
#include <cmath>

namespace pdd {

int noise_scaled_neighbors(double noise, double spacing, int neighbors) {
  if (!(spacing > 0) || !(noise > 0)) return neighbors;
  const double ratio = noise / (0.25 * spacing);
  const double grown = neighbors * ratio * ratio;
  return grown > neighbors ? static_cast<int>(std::min<double>(std::lround(grown), kMaxNoiseNeighbors))
                           : neighbors;
}

std::vector<Vec3> smooth_points(const std::vector<Vec3>& points, int neighbors) {
  using Kernel = CGAL::Simple_cartesian<double>;
  std::vector<Kernel::Point_3> smoothed;
  smoothed.reserve(points.size());
  for (const Vec3& p : points) smoothed.emplace_back(p.x(), p.y(), p.z());
  const auto k = static_cast<unsigned>(std::min<std::size_t>(neighbors, points.size() - 1));
  CGAL::jet_smooth_point_set<CGAL::Parallel_if_available_tag>(smoothed, k);
  std::vector<Vec3> result;
  result.reserve(points.size());
  for (const auto& p : smoothed) result.emplace_back(p.x(), p.y(), p.z());
  return result;
}

}  // namespace pdd
