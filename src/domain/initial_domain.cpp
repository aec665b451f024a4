// Initialization of the domain, §3.2: a loose sphere around the input,
// sampled uniformly, then Delaunay refinement by circumcenter insertion.
#include <pdd/domain.h>
#include <pdd/errors.h>

#include "domain/domain_impl.h"

#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>

#include <cmath>
#include <cstdio>
#include <queue>
#include <string>

namespace pdd {
namespace {

// n points spread uniformly on the sphere (c, r): the Fibonacci lattice,
// deterministic and near-uniform for any n.
std::vector<Vec3> fibonacci_sphere(const Vec3& c, double r, int n) {
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    points.push_back(c + r * Vec3(rho * std::cos(phi), rho * std::sin(phi), z));
  }
  return points;
}

// Smallest enclosing sphere of the input points (exact, CGAL).
void bounding_sphere(const std::vector<Vec3>& points, Vec3& center, double& radius) {
  using Traits = CGAL::Min_sphere_of_points_d_traits_3<detail::Kernel, double>;
  std::vector<detail::Point> p;
  p.reserve(points.size());
  for (const Vec3& v : points) p.push_back(to_point(v));
  CGAL::Min_sphere_of_spheres_d<Traits> ms(p.begin(), p.end());
  auto it = ms.center_cartesian_begin();
  center.x() = *it++;
  center.y() = *it++;
  center.z() = *it;
  radius = ms.radius();
}

// The distance from `center` to the nearest facet of the triangulation's
// convex hull: the largest ball around it that the domain holds.
double hull_inradius(const Delaunay& dt, const Vec3& center) {
  if (dt.dimension() < 3) return 0;
  double nearest = INFINITY;
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    if (!dt.is_infinite(c)) continue;
    const int i = c->index(dt.infinite_vertex());
    const Vec3 a = to_vec(c->vertex((i + 1) % 4)->point());
    const Vec3 b = to_vec(c->vertex((i + 2) % 4)->point());
    const Vec3 d = to_vec(c->vertex((i + 3) % 4)->point());
    const Vec3 normal = (b - a).cross(d - a).normalized();
    nearest = std::min(nearest, std::abs((center - a).dot(normal)));
  }
  return nearest;
}

double circumradius(Delaunay::Cell_handle c) {
  return std::sqrt(CGAL::squared_radius(c->vertex(0)->point(), c->vertex(1)->point(),
                                        c->vertex(2)->point(), c->vertex(3)->point()));
}

double cell_radius_edge(Delaunay::Cell_handle c) {
  return radius_edge_ratio(to_vec(c->vertex(0)->point()), to_vec(c->vertex(1)->point()),
                           to_vec(c->vertex(2)->point()), to_vec(c->vertex(3)->point()));
}

// A bad cell waiting in the refinement queue, identified by its vertices so
// that a cell destroyed by an earlier insertion is recognized.
struct BadCell {
  double ratio;
  long order;  // insertion order: ties broken deterministically
  std::array<Delaunay::Vertex_handle, 4> v;
  bool operator<(const BadCell& o) const {
    return ratio != o.ratio ? ratio < o.ratio : order > o.order;
  }
};

}  // namespace

Domain Domain::initial(const PointSet& input, const DomainOptions& options,
                       RefinementReport* report) {
  if (input.points.empty()) throw InputError("initial domain: the point set is empty");
  if (!(options.enlarge_ratio > 1.0 && options.enlarge_ratio <= DomainOptions::kMaxEnlargeRatio)) {
    char what[160];
    std::snprintf(what, sizeof what, "initial domain: the enlarge ratio must be > 1 and <= %g, got %g",
                  DomainOptions::kMaxEnlargeRatio, options.enlarge_ratio);
    throw InputError(what);
  }
  if (options.sphere_points < 4)
    throw InputError("initial domain: at least 4 sphere points are needed, got " +
                     std::to_string(options.sphere_points));
  if (!(options.radius_edge_bound >= DomainOptions::kMinRadiusEdgeBound)) {
    char what[160];
    std::snprintf(what, sizeof what, "initial domain: the radius-edge bound must be >= %g, got %g",
                  DomainOptions::kMinRadiusEdgeBound, options.radius_edge_bound);
    throw InputError(what);
  }

  Vec3 c;
  double r;
  bounding_sphere(input.points, c, r);
  if (!(r > 0)) throw InputError("initial domain: all points coincide");
  const double R = options.enlarge_ratio * r;

  Domain domain(fibonacci_sphere(c, R, options.sphere_points),
                std::vector<std::uint8_t>(options.sphere_points, kOnBoundarySphere));
  Impl& d = *domain.impl_;
  // The domain is the hull of the sphere points; the input's bounding sphere
  // must fit in it. Whether it does depends on the two options only: the
  // hull of n points reaches a fixed fraction of the sphere's radius.
  const double reach = hull_inradius(d.dt, c) / R;
  if (!(reach * options.enlarge_ratio > 1)) {
    char what[320];
    std::snprintf(what, sizeof what,
                  "initial domain: the hull of %d points on the domain sphere (--sphere-points) "
                  "reaches %.3g of its radius, less than the input's bounding sphere at 1/%g "
                  "(--enlarge-ratio) = %.3g of it; use more points or a ratio above %.3g",
                  options.sphere_points, reach, options.enlarge_ratio, 1 / options.enlarge_ratio,
                  1 / reach);
    throw InputError(what);
  }
  d.center = c;
  d.radius = R;

  const RefinementReport stats =
      domain.delaunay_refine(options.radius_edge_bound, options.max_refinement_points);
  if (report) *report = stats;
  return domain;
}

RefinementReport Domain::delaunay_refine(double radius_edge_bound, int max_points,
                                         double max_circumradius) {
  Impl& d = *impl_;
  d.restore();
  RefinementReport stats;
  std::priority_queue<BadCell> queue;
  long order = 0;
  auto push_if_bad = [&](Delaunay::Cell_handle cell) {
    if (d.dt.is_infinite(cell)) return;
    const double ratio = cell_radius_edge(cell);
    if (ratio > radius_edge_bound || circumradius(cell) > max_circumradius)
      queue.push({ratio, order++, {cell->vertex(0), cell->vertex(1), cell->vertex(2), cell->vertex(3)}});
  };
  for (auto cell = d.dt.finite_cells_begin(); cell != d.dt.finite_cells_end(); ++cell)
    push_if_bad(cell);

  std::vector<Delaunay::Cell_handle> star;
  while (!queue.empty() && stats.inserted < max_points) {
    const BadCell bad = queue.top();
    queue.pop();
    Delaunay::Cell_handle cell;
    if (!d.dt.is_cell(bad.v[0], bad.v[1], bad.v[2], bad.v[3], cell)) continue;

    // The circumcenter, when it lies inside the current hull and the ball.
    // A bad cell whose circumcenter falls outside is left as it is: it lies
    // against the boundary, far from the data, and projecting its
    // circumcenter onto the sphere can cascade into ever smaller boundary
    // cells.
    const Vec3 p = to_vec(d.dt.dual(cell));
    if ((p - d.center).norm() >= d.radius) continue;
    Delaunay::Locate_type lt;
    int li, lj;
    const Delaunay::Cell_handle where = d.dt.locate(to_point(p), lt, li, lj, cell);
    if (d.dt.is_infinite(where)) continue;
    if (lt == Delaunay::VERTEX) continue;
    const double value = d.interpolate_in(where, p, d.f);
    const auto v = d.dt.insert(to_point(p), lt, where, li, lj);
    v->info() = static_cast<int>(d.f.size());
    d.f.push_back(value);
    d.flags.push_back(0);
    ++stats.inserted;
    star.clear();
    d.dt.incident_cells(v, std::back_inserter(star));
    for (auto s : star) push_if_bad(s);
  }
  d.reindex();

  for (const auto& cell : d.cells) {
    const double ratio = cell_radius_edge(cell);
    stats.worst_radius_edge = std::max(stats.worst_radius_edge, ratio);
    if (ratio > radius_edge_bound || circumradius(cell) > max_circumradius) ++stats.remaining_bad;
  }
  return stats;
}

}  // namespace pdd
