// Stray points of a scan (the points stage, DESIGN.md): found by a
// k-nearest-neighbour distance test before the solve, so that they do not
// become blobs. Not in the paper.
#pragma once

#include <pdd/types.h>

#include <cstddef>
#include <vector>

namespace pdd {

struct OutlierOptions {
  // A point is an outlier when its mean distance to its `neighbors` nearest
  // points exceeds `ratio` times that of its neighbours (their median), the
  // latter taken at most at twice the median over all points so that a
  // cluster of outliers cannot vouch for itself. 0 turns the test off.
  double ratio = 3;
  int neighbors = 16;
};

struct OutlierReport {
  std::size_t removed = 0;  // points found to be outliers (and dropped by the pipeline)
  double ratio = 0;         // the options the test ran with (ratio 0: it did not run)
  int neighbors = 0;
  double median_spacing = 0;  // median over the points of their mean neighbour distance
};

// 1 for each point that is an outlier, 0 otherwise. Deterministic, in
// parallel. Fewer than neighbors + 1 points, or ratio 0: none is.
// Throws InputError when ratio is negative or not finite or neighbors < 1.
std::vector<char> find_outliers(const std::vector<Vec3>& points, const OutlierOptions& options = {},
                                OutlierReport* report = nullptr);

}  // namespace pdd
