// The isofacets a_t of §3.3-§3.4: the planar piece of the zero set of a
// piecewise-linear f inside each tet whose vertices change sign.
#pragma once

#include <pdd/types.h>

#include <array>
#include <vector>

namespace pdd {

struct Isofacet {
  int tet = -1;
  int negative_vertices = 0;  // 1 or 3: a triangle (case 1 of §3.4); 2: a quadrangle (case 2)
  int num_corners = 0;        // 3 or 4, in cyclic order
  std::array<Vec3, 4> corners;               // p_e, the crossing points
  std::array<std::array<int, 2>, 4> edges;   // the crossing edge (vertex indices) of each corner
  double area = 0;            // area(a_t)
  Vec3 centroid = Vec3::Zero();  // area-weighted centroid
  Vec3 normal = Vec3::Zero();    // n_{a_t}: unit gradient of f, pointing to f > 0

  bool is_triangle() const { return num_corners == 3; }
  // The larger of the contour's triangles in this facet: a quadrangle is cut
  // along its shorter diagonal, as marching tetrahedra cut it (§3.4).
  double largest_triangle_area() const;
};

// The isofacet of every tet crossed by f = isovalue, in tet order. A value
// equal to the isovalue counts as positive (the project's symbolic
// perturbation), so crossing edges join a value < isovalue to one >= isovalue.
std::vector<Isofacet> isofacets(const TetMesh& mesh, const std::vector<double>& f,
                                double isovalue = 0.0);

// Whether f changes sign over tet t (a value equal to the isovalue counts as
// positive): whether tet t has an isofacet.
bool crosses_isovalue(const TetMesh& mesh, const std::vector<double>& f, int t,
                      double isovalue = 0.0);

// The isofacet of tet t alone: false (and `out` untouched) when f does not
// change sign over it.
bool isofacet(const TetMesh& mesh, const std::vector<double>& f, int t, Isofacet& out,
              double isovalue = 0.0);

}  // namespace pdd
