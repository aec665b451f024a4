// The samples' spacing (spacing.h).
#include "contour/spacing.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

namespace pdd::detail {

namespace {

// Each sample's distance to its nearest other sample.
std::vector<double> nearest_distances(const std::vector<Vec3>& samples, const NearestNeighbors& tree) {
  std::vector<double> nearest(samples.size(), 0.0);
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t i) {
    const std::vector<int> two = tree.query(samples[i], 2);
    for (int j : two)
      if (static_cast<std::size_t>(j) != i) nearest[i] = (samples[j] - samples[i]).norm();
  });
  return nearest;
}

double mean(const std::vector<double>& x) {
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

}  // namespace

double average_spacing(const std::vector<Vec3>& samples, const NearestNeighbors& tree) {
  return mean(nearest_distances(samples, tree));
}

Spacing sample_spacing(const std::vector<Vec3>& samples, const NearestNeighbors& tree, int k) {
  const std::size_t n = samples.size();
  const std::vector<double> nearest = nearest_distances(samples, tree);
  Spacing s;
  s.local.resize(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const std::vector<int> around = tree.query(samples[i], k);
    double sum = 0;
    for (int j : around) sum += nearest[j];
    s.local[i] = sum / static_cast<double>(around.size());
  });
  s.average = mean(nearest);
  for (double& local : s.local) local = std::min(local, 2 * s.average);
  return s;
}

}  // namespace pdd::detail
