// The samples' spacing, private to the contour stage (the trim, the handle cut).
#pragma once

#include <pdd/types.h>

#include <vector>

#include "common/nearest_neighbors.h"

namespace pdd::detail {

// Each sample's local spacing: the mean nearest-neighbour distance over its
// `k` nearest samples, at most twice the average (a lone sample's own distance
// to the rest measures its isolation, not the scan's density, and would widen
// its reach with it); and the samples' average spacing (mean nearest-neighbour distance).
struct Spacing {
  std::vector<double> local;
  double average = 0;
};

Spacing sample_spacing(const std::vector<Vec3>& samples, const NearestNeighbors& tree, int k);

// Only the average spacing.
double average_spacing(const std::vector<Vec3>& samples, const NearestNeighbors& tree);

}  // namespace pdd::detail
