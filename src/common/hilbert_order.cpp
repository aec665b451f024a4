#include "common/hilbert_order.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <numeric>

namespace pdd::detail {

std::vector<int> hilbert_order(const std::vector<Vec3>& points) {
  using Kernel = CGAL::Simple_cartesian<double>;
  std::vector<Kernel::Point_3> copy;
  copy.reserve(points.size());
  for (const Vec3& x : points) copy.emplace_back(x.x(), x.y(), x.z());
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  using Map = CGAL::Pointer_property_map<Kernel::Point_3>::type;
  CGAL::hilbert_sort<CGAL::Parallel_tag>(
      order.begin(), order.end(),
      CGAL::Spatial_sort_traits_adapter_3<Kernel, Map>(CGAL::make_property_map(copy)),
      CGAL::Hilbert_sort_median_policy());
  return std::vector<int>(order.begin(), order.end());
}

}  // namespace pdd::detail
