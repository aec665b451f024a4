// Private to src/: the state behind pdd::Domain, shared by the files of the
// domain stage.
#pragma once

#include <pdd/domain.h>

#include "common/cancellation.h"
#include "domain/triangulation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <vector>

namespace pdd {

using detail::Delaunay;
using detail::to_point;
using detail::to_vec;

struct Domain::Impl {
  Delaunay dt;
  std::vector<Delaunay::Vertex_handle> handles;  // dense index -> vertex
  std::vector<Delaunay::Cell_handle> cells;      // tet index -> cell
  TetMesh mesh;  // the dense arrays: vertex i's position, tet t's corners
  std::vector<std::array<int, 4>> neighbors;
  std::vector<double> f;
  std::vector<std::uint8_t> flags;
  Vec3 center = Vec3::Zero();
  double radius = 0;

  // Rebuilds the dense arrays from the triangulation (vertex infos are the
  // dense indices and must be 0..n-1).
  void reindex() {
    const std::size_t n = dt.number_of_vertices();
    handles.assign(n, Delaunay::Vertex_handle());
    std::vector<Vec3>& vertices = mesh.vertices;
    std::vector<std::array<int, 4>>& tets = mesh.tets;
    vertices.resize(n);
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      handles[v->info()] = v;
      vertices[v->info()] = to_vec(v->point());
    }
    // Sized exactly (not grown by doubling: 1.5x the bytes at ten million tets).
    const std::size_t finite = dt.number_of_finite_cells();
    std::vector<Delaunay::Cell_handle>().swap(cells);
    std::vector<std::array<int, 4>>().swap(tets);
    cells.reserve(finite);
    tets.reserve(finite);
    std::size_t k = 0;  // the run's cancellation is polled along the passes over the cells
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
      c->info() = -1;
      detail::poll_every(++k);
    }
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
      c->info() = static_cast<int>(cells.size());
      cells.push_back(c);
      tets.push_back({c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(),
                      c->vertex(3)->info()});
      detail::poll_every(++k);
    }
    neighbors.resize(cells.size());
    for (std::size_t t = 0; t < cells.size(); ++t) {
      for (int i = 0; i < 4; ++i) neighbors[t][i] = cells[t]->neighbor(i)->info();
      detail::poll_every(t);
    }
  }

  // Bounding sphere of the vertices (used when no domain sphere is known).
  void fit_sphere_to_vertices() {
    if (mesh.vertices.empty()) return;
    Eigen::AlignedBox3d box;
    const std::vector<Vec3>& vertices = mesh.vertices;
    for (const Vec3& v : vertices) box.extend(v);
    center = box.center();
    radius = 0;
    for (const Vec3& v : vertices) radius = std::max(radius, (v - center).norm());
  }

  // A finite cell whose closure contains p, or a null handle when p is
  // outside the hull. Points on the hull can be located in an infinite cell:
  // the finite cell across its finite facet contains them.
  Delaunay::Cell_handle finite_cell_containing(const Vec3& p,
                                               Delaunay::Cell_handle hint = {}) const {
    Delaunay::Locate_type lt;
    int li, lj;
    Delaunay::Cell_handle c = dt.locate(to_point(p), lt, li, lj, hint);
    if (c == Delaunay::Cell_handle() || lt == Delaunay::OUTSIDE_CONVEX_HULL ||
        lt == Delaunay::OUTSIDE_AFFINE_HULL)
      return {};
    if (dt.is_infinite(c)) c = c->neighbor(c->index(dt.infinite_vertex()));
    return c;
  }

  // Barycentric coordinates of p in finite cell c.
  static std::array<double, 4> barycentric(Delaunay::Cell_handle c, const Vec3& p) {
    Vec3 q[4];
    for (int i = 0; i < 4; ++i) q[i] = to_vec(c->vertex(i)->point());
    auto volume = [](const Vec3& a, const Vec3& b, const Vec3& c2, const Vec3& d) {
      return (b - a).dot((c2 - a).cross(d - a));
    };
    const double total = volume(q[0], q[1], q[2], q[3]);
    std::array<double, 4> w;
    w[0] = volume(p, q[1], q[2], q[3]) / total;
    w[1] = volume(q[0], p, q[2], q[3]) / total;
    w[2] = volume(q[0], q[1], p, q[3]) / total;
    w[3] = 1.0 - w[0] - w[1] - w[2];
    return w;
  }

  // The tet c (null: outside) and p's barycentric coordinates in it.
  static Location location(Delaunay::Cell_handle c, const Vec3& p) {
    Location loc;
    if (c == Delaunay::Cell_handle()) return loc;
    loc.tet = c->info();
    loc.barycentric = barycentric(c, p);
    return loc;
  }

  double interpolate_in(Delaunay::Cell_handle c, const Vec3& p,
                        const std::vector<double>& values) const {
    const auto w = barycentric(c, p);
    double s = 0;
    for (int i = 0; i < 4; ++i) s += w[i] * values[c->vertex(i)->info()];
    return s;
  }

  // Builds the triangulation of `points` with vertex info = position in the
  // input; duplicates are merged and the survivors renumbered densely.
  // Returns, for each survivor's new index, its index in `points`.
  std::vector<int> build(const std::vector<Vec3>& points) {
    dt.clear();
    std::vector<std::pair<detail::Point, int>> items;
    items.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      items.emplace_back(to_point(points[i]), static_cast<int>(i));
    dt.insert(items.begin(), items.end());
    std::vector<int> original;
    original.reserve(dt.number_of_vertices());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
      original.push_back(v->info());
    std::sort(original.begin(), original.end());
    std::vector<int> rank(points.size(), -1);
    for (std::size_t i = 0; i < original.size(); ++i) rank[original[i]] = static_cast<int>(i);
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
      v->info() = rank[v->info()];
    reindex();
    return original;
  }
};

}  // namespace pdd
