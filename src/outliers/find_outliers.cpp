// The outlier test of outliers.h. CGAL's remove_outliers compares each
// point's neighbour distance with one global threshold, which removes the
// sparse parts of a scan of varying density (bunny_vardens, building.ply) long
// before it catches the outliers near the surface; this test compares a point
// with its own neighbourhood (docs/benchmarks.md, "Outliers").
#include <pdd/errors.h>
#include <pdd/outliers.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"

namespace pdd {

namespace {

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::vector<char> find_outliers(const std::vector<Vec3>& points, const OutlierOptions& options,
                                OutlierReport* report) {
  if (!(options.ratio >= 0) || !std::isfinite(options.ratio))
    throw InputError("outliers: the ratio must be a number >= 0, got " +
                     std::to_string(options.ratio));
  if (options.neighbors < 1)
    throw InputError("outliers: at least one neighbour is needed, got " +
                     std::to_string(options.neighbors));
  const std::size_t n = points.size();
  const auto k = static_cast<std::size_t>(options.neighbors);
  std::vector<char> outlier(n, 0);
  if (report) *report = {0, options.ratio, options.neighbors, 0};
  if (options.ratio == 0 || n < k + 1) return outlier;

  const detail::NearestNeighbors tree(points);
  std::vector<int> neighbours(n * k);
  std::vector<double> spacing(n);  // mean distance to the k nearest other points
  detail::polled_parallel_for(n, [&](std::size_t s) {
    const auto i = static_cast<std::size_t>(tree.spatial_order()[s]);  // the tree's order: cached paths
    const std::vector<int> nearest = tree.query(points[i], options.neighbors + 1);
    std::size_t found = 0;
    double sum = 0;
    for (int j : nearest) {
      if (static_cast<std::size_t>(j) == i || found == k) continue;
      neighbours[i * k + found++] = j;
      sum += (points[j] - points[i]).norm();
    }
    spacing[i] = sum / static_cast<double>(found);
    for (; found < k; ++found) neighbours[i * k + found] = static_cast<int>(i);
  });
  const double typical = median(spacing);
  detail::polled_parallel_for(n, [&](std::size_t i) {
    std::vector<double> around(k);
    for (std::size_t j = 0; j < k; ++j) around[j] = spacing[neighbours[i * k + j]];
    const double local = std::min(median(std::move(around)), 2 * typical);
    outlier[i] = spacing[i] > options.ratio * local ? 1 : 0;
  });
  if (report) {
    report->removed = static_cast<std::size_t>(std::count(outlier.begin(), outlier.end(), 1));
    report->median_spacing = typical;
  }
  return outlier;
}

}  // namespace pdd
