// Point location on a released domain: a visibility walk over the tets'
// arrays, so that locating points (the optimizer's guard, the solves'
// samples) does not rebuild CGAL's triangulation. Written here because
// CGAL's walks need its triangulation; the predicate is CGAL's exact
// orientation, so the walk is as robust as CGAL's.
#include "domain/domain_impl.h"

namespace pdd {

Location Domain::Impl::walk(const Vec3& p, int start) const {
  const std::vector<std::array<int, 4>>& tets = mesh.tets;
  const std::vector<Vec3>& x = mesh.vertices;
  const detail::Point q = to_point(p);
  int t = start;
  // A visibility walk terminates in a Delaunay triangulation whichever
  // separating face it crosses (Edelsbrunner 1989): at most every tet once.
  for (std::size_t steps = 0; steps <= tets.size(); ++steps) {
    const std::array<int, 4>& k = tets[t];
    const detail::Point a[4] = {to_point(x[k[0]]), to_point(x[k[1]]), to_point(x[k[2]]),
                                to_point(x[k[3]])};
    int exit = -1;
    for (int i = 0; i < 4 && exit < 0; ++i) {
      detail::Point b[4] = {a[0], a[1], a[2], a[3]};
      b[i] = q;
      if (CGAL::orientation(b[0], b[1], b[2], b[3]) == CGAL::NEGATIVE) exit = i;
    }
    if (exit < 0) {  // on the inner side of all four faces: inside t or on its boundary
      Location loc;
      loc.tet = t;
      const Vec3 corners[4] = {x[k[0]], x[k[1]], x[k[2]], x[k[3]]};
      loc.barycentric = barycentric(corners, p);
      return loc;
    }
    t = neighbors[t][exit];
    if (t < 0) return Location();  // beyond a hull face: outside the convex hull
  }
  throw std::logic_error("Domain: the walk did not end: the tets are not a Delaunay triangulation");
}

}  // namespace pdd
