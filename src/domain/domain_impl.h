// Private to src/: the state behind pdd::Domain, shared by the files of the
// domain stage.
#pragma once

#include <pdd/domain.h>

#include "common/cancellation.h"
#include "domain/concurrent_delaunay.h"
#include "domain/triangulation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace pdd {

using detail::Delaunay;
using detail::to_point;
using detail::to_vec;

struct Domain::Impl {
  // The triangulation and its handles are a cache of the dense arrays below:
  // Domain::release_triangulation frees them, restore() rebuilds them.
  mutable Delaunay dt;
  mutable std::vector<Delaunay::Vertex_handle> handles;  // dense index -> vertex
  mutable std::vector<Delaunay::Cell_handle> cells;      // tet index -> cell
  TetMesh mesh;  // the dense arrays: vertex i's position, tet t's corners
  std::vector<std::array<int, 4>> neighbors;
  std::vector<double> f;
  std::vector<std::uint8_t> flags;
  Vec3 center = Vec3::Zero();
  double radius = 0;
  mutable std::atomic<bool> released{false};
  mutable std::mutex restoring;
  // While released: the cell each vertex (the infinite one last) pointed to,
  // where point location starts its walks (a finite tet's index, or -2 - (4 t
  // + i) for the infinite cell across face i of tet t).
  mutable std::vector<int> released_vertex_cells;

  // Frees the triangulation (about 500 bytes per vertex), keeping the arrays.
  void release() const {
    std::lock_guard<std::mutex> lock(restoring);
    if (released.load()) return;
    if (dt.dimension() == 3) {
      auto encode = [&](Delaunay::Cell_handle c) {
        if (!dt.is_infinite(c)) return c->info();
        const Delaunay::Cell_handle finite = c->neighbor(c->index(dt.infinite_vertex()));
        return -2 - (4 * finite->info() + finite->index(c));
      };
      released_vertex_cells.resize(handles.size() + 1);
      for (std::size_t i = 0; i < handles.size(); ++i)
        released_vertex_cells[i] = encode(handles[i]->cell());
      released_vertex_cells.back() = encode(dt.infinite_vertex()->cell());
    }
    Delaunay().swap(dt);
    std::vector<Delaunay::Vertex_handle>().swap(handles);
    std::vector<Delaunay::Cell_handle>().swap(cells);
    released.store(true);
  }

  // Rebuilds a released triangulation from the arrays (with no predicate; the
  // arrays keep their order). Safe to call from concurrent readers.
  void restore() const {
    if (!released.load(std::memory_order_acquire)) return;
    std::lock_guard<std::mutex> lock(restoring);
    if (!released.load(std::memory_order_relaxed)) return;
    const std::vector<std::array<int, 4>>& tets = mesh.tets;
    if (tets.empty()) {  // fewer than three dimensions: no cells to keep
      std::vector<std::pair<detail::Point, int>> items;
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        items.emplace_back(to_point(mesh.vertices[i]), static_cast<int>(i));
      dt.insert(items.begin(), items.end());
      handles.assign(mesh.vertices.size(), Delaunay::Vertex_handle());
      for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        handles[v->info()] = v;
      released.store(false, std::memory_order_release);
      return;
    }
    // released_vertex_cells stays: concurrent walks may still read it.
    detail::triangulation_from_arrays(mesh, neighbors, released_vertex_cells, dt, handles, cells);
    released.store(false, std::memory_order_release);
  }

  // The Delaunay tets of the vertices, built on all cores, as the arrays with
  // the triangulation released (false, nothing changed, when two coincide).
  bool delaunay_arrays();

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

  // Barycentric coordinates of p in the tet q (positively oriented).
  static std::array<double, 4> barycentric(const Vec3 (&q)[4], const Vec3& p) {
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

  // Barycentric coordinates of p in finite cell c.
  static std::array<double, 4> barycentric(Delaunay::Cell_handle c, const Vec3& p) {
    Vec3 q[4];
    for (int i = 0; i < 4; ++i) q[i] = to_vec(c->vertex(i)->point());
    return barycentric(q, p);
  }

  // While released: point location by a walk over the arrays from tet
  // `start` (walk.cpp), and the tet a vertex's walks start from.
  Location walk(const Vec3& p, int start) const;
  bool walkable() const {
    return released.load(std::memory_order_acquire) && !mesh.tets.empty();
  }
  int start_tet(int vertex) const {
    const int code = released_vertex_cells.at(vertex);
    return code >= 0 ? code : (-2 - code) / 4;
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
