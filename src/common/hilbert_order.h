// Private to src/: an order of points along a Hilbert curve, so that
// consecutive items are near in space (and in cache).
#pragma once

#include <pdd/types.h>

#include <vector>

namespace pdd::detail {

// The indices of `points` along a Hilbert curve (CGAL's median policy),
// sorted on all cores: the same order whatever the threads.
std::vector<int> hilbert_order(const std::vector<Vec3>& points);

}  // namespace pdd::detail
