#include "common/nearest_neighbors.h"

#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <boost/iterator/counting_iterator.hpp>

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

struct NearestNeighbors::Impl {
  std::vector<Point> points;
  std::unique_ptr<Tree> tree;
};

NearestNeighbors::NearestNeighbors(const std::vector<Vec3>& points)
    : impl_(std::make_unique<Impl>()) {
  impl_->points.reserve(points.size());
  for (const Vec3& p : points) impl_->points.emplace_back(p.x(), p.y(), p.z());
  impl_->tree = std::make_unique<Tree>(boost::counting_iterator<std::size_t>(0),
                                       boost::counting_iterator<std::size_t>(points.size()),
                                       Tree::Splitter(),
                                       Traits(CGAL::make_property_map(impl_->points)));
  impl_->tree->build();  // built once here so that queries are read-only
}

NearestNeighbors::~NearestNeighbors() = default;

std::vector<int> NearestNeighbors::query(const Vec3& q, int k) const {
  const Distance distance(CGAL::make_property_map(impl_->points));
  Search search(*impl_->tree, Point(q.x(), q.y(), q.z()), static_cast<unsigned>(k), 0, true,
                distance);
  std::vector<int> out;
  out.reserve(k);
  for (auto it = search.begin(); it != search.end(); ++it) out.push_back(static_cast<int>(it->first));
  return out;
}

std::vector<int> NearestNeighbors::within(const Vec3& q, double radius) const {
  std::vector<std::size_t> found;
  const Traits traits(CGAL::make_property_map(impl_->points));
  impl_->tree->search(std::back_inserter(found),
                      CGAL::Fuzzy_sphere<Traits>(Point(q.x(), q.y(), q.z()), radius, 0.0, traits));
  return std::vector<int>(found.begin(), found.end());
}

}  // namespace pdd::detail
