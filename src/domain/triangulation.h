// CGAL types of the domain, private to src/. A Delaunay triangulation whose
// vertices carry their dense index and whose cells carry their tet index.
#pragma once

#include <pdd/types.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

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

}  // namespace pdd::detail
