// CGAL types of the domain, private to src/. A Delaunay triangulation whose
// vertices carry their dense index and whose cells carry their tet index.
#pragma once

#include <pdd/types.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <numeric>
#include <vector>

namespace pdd::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<
    int, Kernel, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

inline Point to_point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }
inline Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// The indices of `points` in CGAL's spatial (Hilbert, BRIO) order, the order
// its range insertion uses: each point near the one before it. Sorted on all
// cores (the same order on any number: fixed splits, a fixed shuffle).
inline std::vector<std::size_t> spatial_order(const std::vector<Point>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  CGAL::spatial_sort<CGAL::Parallel_tag>(
      order.begin(), order.end(),
      CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::Pointer_property_map<Point>::const_type>(
          CGAL::make_property_map(points)));
  return order;
}

}  // namespace pdd::detail
