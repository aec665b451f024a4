// k-nearest-neighbour queries over a fixed set of points (CGAL kd-tree).
// Private to src/. Queries are const and may run concurrently.
#pragma once

#include <pdd/types.h>

#include <memory>
#include <vector>

namespace pdd::detail {

class NearestNeighbors {
 public:
  explicit NearestNeighbors(const std::vector<Vec3>& points);
  ~NearestNeighbors();
  // Indices of the k points nearest to q, nearest first (fewer if the set is smaller).
  std::vector<int> query(const Vec3& q, int k) const;
  // Indices of the points within `radius` of q, in an order fixed by the tree.
  std::vector<int> within(const Vec3& q, double radius) const;
  // The points' indices in spatial (Hilbert) order, the tree's own: queries
  // from every point run 3-4x faster in this order than in a random one (a
  // scan's points often come shuffled) as their paths through the tree are
  // still in the cache.
  const std::vector<int>& spatial_order() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pdd::detail
