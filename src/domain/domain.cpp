// The discrete domain: a CGAL Delaunay triangulation with dense vertex
// indices, a per-vertex function f and per-vertex flags.
#include <pdd/domain.h>

#include "common/cancellation.h"
#include "domain/concurrent_delaunay.h"
#include "domain/domain_impl.h"

#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace pdd {

Domain::Domain() : impl_(std::make_unique<Impl>()) {}

Domain::Domain(const std::vector<Vec3>& points, const std::vector<std::uint8_t>& flags)
    : impl_(std::make_unique<Impl>()) {
  if (!flags.empty() && flags.size() != points.size())
    throw std::invalid_argument("Domain: one flag per point is required");
  const std::vector<int> original = impl_->build(points);
  impl_->f.assign(original.size(), 0.0);
  impl_->flags.assign(original.size(), 0);
  if (!flags.empty())
    for (std::size_t i = 0; i < original.size(); ++i) impl_->flags[i] = flags[original[i]];
  impl_->fit_sphere_to_vertices();
}

Domain::Domain(Domain&&) noexcept = default;
Domain& Domain::operator=(Domain&&) noexcept = default;
Domain::~Domain() = default;

Domain::Domain(const Domain& other) : impl_(std::make_unique<Impl>()) {
  const Impl& o = *other.impl_;
  if (o.released.load()) {  // a copy of the arrays, released too
    impl_->mesh = o.mesh;
    impl_->neighbors = o.neighbors;
    impl_->released_vertex_cells = o.released_vertex_cells;
    impl_->released.store(true);
  } else {
    impl_->dt = o.dt;
    impl_->reindex();
  }
  impl_->f = o.f;
  impl_->flags = o.flags;
  impl_->center = o.center;
  impl_->radius = o.radius;
}

Domain& Domain::operator=(const Domain& other) {
  if (this != &other) *this = Domain(other);
  return *this;
}

std::size_t Domain::num_vertices() const { return impl_->mesh.vertices.size(); }
std::size_t Domain::num_tets() const { return impl_->mesh.tets.size(); }
const std::vector<Vec3>& Domain::vertices() const { return impl_->mesh.vertices; }
const std::vector<std::array<int, 4>>& Domain::tets() const { return impl_->mesh.tets; }
const std::vector<std::array<int, 4>>& Domain::tet_neighbors() const { return impl_->neighbors; }
const TetMesh& Domain::mesh() const { return impl_->mesh; }
const std::vector<double>& Domain::f() const { return impl_->f; }

void Domain::set_f(std::vector<double> values) {
  if (values.size() != num_vertices())
    throw std::invalid_argument("Domain::set_f: one value per vertex is required");
  impl_->f = std::move(values);
}

const std::vector<std::uint8_t>& Domain::flags() const { return impl_->flags; }
bool Domain::on_boundary_sphere(int vertex) const {
  return impl_->flags[vertex] & kOnBoundarySphere;
}
Vec3 Domain::center() const { return impl_->center; }
double Domain::radius() const { return impl_->radius; }

// A released domain is walked over its arrays (no triangulation rebuilt);
// a live one by CGAL's walk.
Location Domain::locate(const Vec3& p) const {
  if (impl_->walkable()) return impl_->walk(p, 0);
  impl_->restore();
  return Impl::location(impl_->finite_cell_containing(p), p);
}

Location Domain::locate(const Vec3& p, int near_vertex) const {
  if (impl_->walkable()) return impl_->walk(p, impl_->start_tet(near_vertex));
  impl_->restore();
  return Impl::location(impl_->finite_cell_containing(p, impl_->handles.at(near_vertex)->cell()),
                        p);
}

Location Domain::locate(const Vec3& p, const Location& near) const {
  if (impl_->walkable()) return impl_->walk(p, near.tet);
  return locate(p, impl_->mesh.tets.at(near.tet)[0]);
}

double Domain::interpolate(const Vec3& p, const std::vector<double>& values) const {
  impl_->restore();
  const auto c = impl_->finite_cell_containing(p);
  if (c == Delaunay::Cell_handle())
    throw std::out_of_range("Domain::interpolate: point outside the domain");
  return impl_->interpolate_in(c, p, values);
}

double Domain::interpolate(const Location& at, const std::vector<double>& values) const {
  if (at.tet < 0 || at.tet >= static_cast<int>(impl_->mesh.tets.size()))
    throw std::out_of_range("Domain::interpolate: the location is outside the domain");
  const auto& tet = impl_->mesh.tets[at.tet];
  double s = 0;
  for (int i = 0; i < 4; ++i) s += at.barycentric[i] * values[tet[i]];
  return s;
}

std::vector<int> Domain::insert(const std::vector<Vec3>& points, std::uint8_t flags) {
  Impl& d = *impl_;
  d.restore();
  // In spatial order (CGAL's Hilbert sort): each point is located from the
  // last one, and the new vertices are numbered along the curve, so that
  // neighbours have near indices (the solvers' sparse products read the
  // vertex arrays at the indices of a row: 1.2-1.5x faster than in the
  // refiner's order at 400k vertices, docs/benchmarks.md).
  using Item = std::pair<detail::Point, int>;
  std::vector<Item> order;
  order.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    order.emplace_back(to_point(points[i]), static_cast<int>(i));
  CGAL::spatial_sort<CGAL::Parallel_tag>(
      order.begin(), order.end(),
      CGAL::Spatial_sort_traits_adapter_3<detail::Kernel, CGAL::First_of_pair_property_map<Item>>());
  // Values are taken from the current interpolant before any insertion, so
  // that the order of insertion does not change them.
  std::vector<double> values(points.size());
  Delaunay::Cell_handle hint;
  std::size_t located = 0;
  for (const auto& [point, i] : order) {
    detail::poll_every(++located);  // the run's cancellation
    hint = d.finite_cell_containing(points[i], hint);
    if (hint == Delaunay::Cell_handle())
      throw std::invalid_argument("Domain::insert: point outside the domain");
    values[i] = d.interpolate_in(hint, points[i], d.f);
  }
  std::vector<int> label(points.size(), -1);
  Delaunay::Vertex_handle last;
  std::size_t inserted = 0;
  for (const auto& [point, i] : order) {
    if (++inserted % 1024 == 0) detail::poll();  // the run's cancellation
    Delaunay::Locate_type lt;
    int li, lj;
    const auto c = d.dt.locate(point, lt, li, lj,
                               last == Delaunay::Vertex_handle() ? Delaunay::Cell_handle()
                                                                 : last->cell());
    if (lt == Delaunay::VERTEX) continue;
    const auto v = d.dt.insert(point, lt, c, li, lj);
    v->info() = static_cast<int>(d.f.size());
    label[i] = v->info();
    d.f.push_back(values[i]);
    d.flags.push_back(flags);
    last = v;
  }
  d.reindex();
  std::vector<int> added;
  for (int l : label)
    if (l >= 0) added.push_back(l);
  return added;
}

Domain Domain::moved(const std::vector<Vec3>& new_positions) const {
  const Impl& d = *impl_;
  d.restore();
  const std::size_t n = num_vertices();
  if (new_positions.size() != n)
    throw std::invalid_argument("Domain::move_vertices: one position per vertex is required");
  // f at the new positions, interpolated in the old triangulation; a vertex
  // that left the old domain keeps its value.
  std::vector<double> f(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = d.finite_cell_containing(new_positions[i], d.handles[i]->cell());
    f[i] = c == Delaunay::Cell_handle() ? d.f[i] : d.interpolate_in(c, new_positions[i], d.f);
    detail::poll_every(i);  // the run's cancellation
  }
  return moved(new_positions, std::move(f));
}

Domain Domain::moved(std::vector<Vec3> new_positions, std::vector<double> f) const {
  const Impl& d = *impl_;
  const std::size_t n = num_vertices();
  if (new_positions.size() != n || f.size() != n)
    throw std::invalid_argument(
        "Domain::move_vertices: one position and value per vertex is required");
  Domain out;
  Impl& o = *out.impl_;
  o.f = std::move(f);
  o.mesh.vertices = std::move(new_positions);
  if (!o.delaunay_arrays())
    throw std::invalid_argument("Domain::move_vertices: two vertices would coincide");
  o.flags = d.flags;
  o.center = d.center;
  o.radius = d.radius;
  return out;
}

bool Domain::Impl::delaunay_arrays() {
  // Built on all cores and handed over as the arrays, released: points are
  // located by walking them, and the triangulation is restored from them
  // when an insertion or interpolation needs it (restore()).
  detail::DelaunayArrays built = detail::concurrent_delaunay(mesh.vertices);
  if (built.vertices != mesh.vertices.size()) return false;
  mesh.tets = std::move(built.tets);
  neighbors = std::move(built.neighbors);
  released_vertex_cells = std::move(built.vertex_cells);
  released.store(true);
  return true;
}

void Domain::release_triangulation() const { impl_->release(); }

void Domain::release_tets() {
  Impl& d = *impl_;
  d.release();
  std::vector<std::array<int, 4>>().swap(d.mesh.tets);
  std::vector<std::array<int, 4>>().swap(d.neighbors);
  std::vector<int>().swap(d.released_vertex_cells);
}

void Domain::rebuild_tets() {
  Impl& d = *impl_;
  d.release();
  if (!d.delaunay_arrays())
    throw std::logic_error("Domain::rebuild_tets: two of the domain's vertices coincide");
}

bool Domain::triangulation_released() const { return impl_->released.load(); }

void Domain::move_vertices(const std::vector<Vec3>& new_positions) {
  *this = moved(new_positions);
}

void Domain::translate(const Vec3& offset) {
  Impl& d = *impl_;
  if (d.released.load()) {  // restore() builds the triangulation at the moved vertices
    for (Vec3& p : d.mesh.vertices) p += offset;
    d.center += offset;
    return;
  }
  for (auto v = d.dt.finite_vertices_begin(); v != d.dt.finite_vertices_end(); ++v) {
    const Vec3 p = to_vec(v->point()) + offset;
    v->set_point(to_point(p));
    d.mesh.vertices[v->info()] = p;
  }
  d.center += offset;
}

double radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 cc = to_vec(CGAL::circumcenter(to_point(a), to_point(b), to_point(c), to_point(d)));
  const double shortest = std::sqrt(std::min({(a - b).squaredNorm(), (a - c).squaredNorm(),
                                              (a - d).squaredNorm(), (b - c).squaredNorm(),
                                              (b - d).squaredNorm(), (c - d).squaredNorm()}));
  return (cc - a).norm() / shortest;
}

}  // namespace pdd
