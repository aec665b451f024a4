// Normals near sharp features from the most planar neighbourhood that holds
// the point (normals.h). Hand-written: CGAL's feature-aware tools either move
// the points (bilateral_smooth_point_set, edge_aware_upsample_point_set) or
// only flag the edges (vcm_is_on_feature_edge); neither picks a neighbourhood
// that stays on one side of the edge.
#include <pdd/normals.h>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"

#include <algorithm>
#include <cmath>

namespace pdd {
namespace {

// A neighbour's neighbourhood replaces a point's own when its surface
// variation is under this share of the point's (0.02-0.1 give the same
// distances on the shared data: docs/benchmarks.md, "Normals")...
constexpr double kPlanarer = 0.1;
// ...and the point lies on its plane: within its spread, and this slope over
// the step between the two points.
constexpr double kSlope = 0.05;

}  // namespace

std::vector<Vec3> sharpen_normals(const std::vector<Vec3>& points, const JetFits& fits,
                                  int neighbors, std::size_t* replaced) {
  std::vector<Vec3> sharpened = fits.normals;
  if (replaced) *replaced = 0;
  if (points.size() < kMinPointsForNormals) return sharpened;
  const int k = std::min<int>(neighbors, static_cast<int>(points.size()) - 1);
  const std::vector<LocalPlane>& planes = fits.planes;
  const detail::NearestNeighbors tree(points);
  const std::vector<int>& order = tree.spatial_order();  // queries in cache order
  std::vector<int> source(points.size());
  detail::polled_parallel_ranges(points.size(), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const int i = order[s];
      int best = i;
      for (int j : tree.query(points[i], k + 1)) {
        const LocalPlane& q = planes[j];
        const double off = std::abs((points[i] - q.centre).dot(q.normal));
        if (off <= kSlope * (points[i] - points[j]).norm() + 2 * q.thickness &&
            q.variation < planes[best].variation)
          best = j;
      }
      source[i] = planes[best].variation < kPlanarer * planes[i].variation ? best : i;
    }
  });
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (source[i] == static_cast<int>(i)) continue;
    const Vec3& n = fits.normals[source[i]];
    sharpened[i] = n.dot(fits.normals[i]) < 0 ? -n : n;
    if (replaced) ++*replaced;
  }
  return sharpened;
}

}  // namespace pdd
