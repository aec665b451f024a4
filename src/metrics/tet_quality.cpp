// Shape of tetrahedra: dihedral angles and radius-edge ratio (§2.2, §3.2).
#include <pdd/domain.h>
#include <pdd/quality.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "metrics/elements.h"

namespace pdd {

std::array<double, 6> dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // At edge (p, q) with opposite corners r, s: the angle between e x (r - p)
  // and e x (s - p), e = q - p, i.e. between the projections of r and s on
  // the plane normal to e, which is the dihedral angle.
  const Vec3* v[4] = {&a, &b, &c, &d};
  static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                       {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  std::array<double, 6> angles;
  for (int k = 0; k < 6; ++k) {
    const Vec3& p = *v[kEdges[k][0]];
    const Vec3 e = *v[kEdges[k][1]] - p;
    const Vec3 n1 = e.cross(*v[kEdges[k][2]] - p);
    const Vec3 n2 = e.cross(*v[kEdges[k][3]] - p);
    angles[k] = detail::angle_degrees(n1, n2);
  }
  return angles;
}

namespace {

// The shape of every tet, in parallel; also the six dihedral angles of each
// when `angles` is given.
std::vector<TetShape> measure(const TetMesh& mesh, std::vector<std::array<double, 6>>* angles) {
  detail::check_indices(mesh.tets, mesh.vertices.size(), "tet");
  std::vector<TetShape> shapes(mesh.tets.size());
  if (angles) angles->resize(mesh.tets.size());
  tbb::parallel_for(std::size_t(0), mesh.tets.size(), [&](std::size_t i) {
    const auto& t = mesh.tets[i];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]],
               &d = mesh.vertices[t[3]];
    const auto dihedral = dihedral_angles(a, b, c, d);
    const auto [lo, hi] = std::minmax_element(dihedral.begin(), dihedral.end());
    // A flat tet has no finite circumradius: its ratio is infinite.
    const double ratio = radius_edge_ratio(a, b, c, d);
    shapes[i] =
        TetShape{*lo, *hi, std::isfinite(ratio) ? ratio : std::numeric_limits<double>::infinity()};
    if (angles) (*angles)[i] = dihedral;
  });
  return shapes;
}

}  // namespace

std::vector<TetShape> tet_shapes(const TetMesh& mesh) { return measure(mesh, nullptr); }

TetQuality tet_quality(const TetMesh& mesh) {
  std::vector<std::array<double, 6>> angles;
  const std::vector<TetShape> shapes = measure(mesh, &angles);
  TetQuality q;
  q.count = shapes.size();
  std::vector<double> all_angles;
  all_angles.reserve(6 * q.count);
  for (const auto& a : angles) all_angles.insert(all_angles.end(), a.begin(), a.end());
  q.dihedral_histogram = histogram(all_angles, 0.0, 180.0, 18);
  if (q.count == 0) return q;
  q.min_dihedral = q.min_radius_edge = std::numeric_limits<double>::infinity();
  double sum_min_dihedral = 0, sum_radius_edge = 0;
  std::size_t below_10 = 0;
  for (const TetShape& s : shapes) {
    q.min_dihedral = std::min(q.min_dihedral, s.min_dihedral);
    q.max_dihedral = std::max(q.max_dihedral, s.max_dihedral);
    q.min_radius_edge = std::min(q.min_radius_edge, s.radius_edge);
    q.max_radius_edge = std::max(q.max_radius_edge, s.radius_edge);
    sum_min_dihedral += s.min_dihedral;
    sum_radius_edge += s.radius_edge;
    if (s.min_dihedral < 10.0) ++below_10;
  }
  const double n = static_cast<double>(q.count);
  q.mean_min_dihedral = sum_min_dihedral / n;
  q.mean_radius_edge = sum_radius_edge / n;
  q.fraction_min_dihedral_below_10 = below_10 / n;
  return q;
}

}  // namespace pdd
