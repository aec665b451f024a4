#include "common/nearest_neighbors.h"

#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <boost/iterator/counting_iterator.hpp>

#include <numeric>

namespace pdd::detail {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;
using Distance = Search::Distance;

}  // namespace

// The tree holds the points in spatial order (points[k] is the input's point
// order[k]), so that a leaf's points sit together in memory: random queries
// 1.3x faster at 1M points, 3.9x with queries in that order too.
struct NearestNeighbors::Impl {
  std::vector<Point> points;
  std::vector<int> order;
  std::unique_ptr<Tree> tree;
};

NearestNeighbors::NearestNeighbors(const std::vector<Vec3>& points)
    : impl_(std::make_unique<Impl>()) {
  const std::size_t n = points.size();
  std::vector<Point> input;
  input.reserve(n);
  for (const Vec3& p : points) input.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  CGAL::spatial_sort<CGAL::Parallel_tag>(
      order.begin(), order.end(),
      CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::Pointer_property_map<Point>::const_type>(
          CGAL::make_property_map(static_cast<const std::vector<Point>&>(input))));
  impl_->points.reserve(n);
  impl_->order.reserve(n);
  for (std::size_t i : order) {
    impl_->points.push_back(input[i]);
    impl_->order.push_back(static_cast<int>(i));
  }
  impl_->tree = std::make_unique<Tree>(boost::counting_iterator<std::size_t>(0),
                                       boost::counting_iterator<std::size_t>(n),
                                       Tree::Splitter(),
                                       Traits(CGAL::make_property_map(impl_->points)));
  impl_->tree->build();  // built once here so that queries are read-only
}

const std::vector<int>& NearestNeighbors::spatial_order() const { return impl_->order; }

NearestNeighbors::~NearestNeighbors() = default;

std::vector<int> NearestNeighbors::query(const Vec3& q, int k) const {
  const Distance distance(CGAL::make_property_map(impl_->points));
  Search search(*impl_->tree, Point(q.x(), q.y(), q.z()), static_cast<unsigned>(k), 0, true,
                distance);
  std::vector<int> out;
  out.reserve(k);
  for (auto it = search.begin(); it != search.end(); ++it)
    out.push_back(impl_->order[it->first]);
  return out;
}

std::vector<int> NearestNeighbors::within(const Vec3& q, double radius) const {
  std::vector<std::size_t> found;
  const Traits traits(CGAL::make_property_map(impl_->points));
  impl_->tree->search(std::back_inserter(found),
                      CGAL::Fuzzy_sphere<Traits>(Point(q.x(), q.y(), q.z()), radius, 0.0, traits));
  std::vector<int> out;
  out.reserve(found.size());
  for (std::size_t k : found) out.push_back(impl_->order[k]);
  return out;
}

}  // namespace pdd::detail
