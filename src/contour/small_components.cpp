// Removal of stray components of the output (contour.h): those below its
// resolution, and those cut open by the domain's boundary.
#include <pdd/contour.h>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"
#include "common/union_find.h"
#include "contour/components.h"

namespace pdd {

namespace detail {

using detail::find_root;

Components components(const TriangleMesh& mesh) {
  std::vector<int> parent = singletons(mesh.vertices.size());
  for (std::size_t k = 0; k < mesh.faces.size(); ++k) {
    const auto& f = mesh.faces[k];
    for (int i = 0; i < 3; ++i) parent[find_root(parent, f[i])] = find_root(parent, f[(i + 1) % 3]);
    detail::poll_every(k);  // the run's cancellation
  }
  Components c;
  c.root_of.resize(parent.size());
  for (std::size_t v = 0; v < parent.size(); ++v)
    c.root_of[v] = find_root(parent, static_cast<int>(v));
  c.faces.assign(parent.size(), 0);
  for (const auto& f : mesh.faces) ++c.faces[c.root_of[f[0]]];
  c.largest = static_cast<int>(std::max_element(c.faces.begin(), c.faces.end()) - c.faces.begin());
  return c;
}

std::vector<Eigen::AlignedBox3d> component_boxes(const TriangleMesh& mesh, const Components& c) {
  std::vector<Eigen::AlignedBox3d> box(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (int v : f) box[c.root_of[f[0]]].extend(mesh.vertices[v]);
  return box;
}

RemovedComponents remove_marked(TriangleMesh& mesh, const Components& c,
                                const std::vector<char>& marked) {
  RemovedComponents report;
  for (std::size_t r = 0; r < marked.size(); ++r)
    if (marked[r]) {
      ++report.components;
      report.faces += c.faces[r];
    }
  if (report.components == 0) return report;
  std::vector<std::array<int, 3>> kept;
  for (const auto& f : mesh.faces)
    if (!marked[c.root_of[f[0]]]) kept.push_back(f);
  mesh.faces = std::move(kept);
  drop_unused_vertices(mesh);
  return report;
}

void drop_unused_vertices(TriangleMesh& mesh) {
  std::vector<int> index(mesh.vertices.size(), -1);
  for (const auto& f : mesh.faces)
    for (int v : f) index[v] = 0;
  std::size_t used = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int>(used);
      mesh.vertices[used++] = mesh.vertices[v];
    }
  mesh.vertices.resize(used);
  for (auto& f : mesh.faces)
    for (int& v : f) v = index[v];
}

}  // namespace detail

using detail::Components;
using detail::components;
using detail::remove_marked;

RemovedComponents remove_small_components(TriangleMesh& mesh, double min_edges) {
  if (!(min_edges >= 0) || !std::isfinite(min_edges))
    throw std::invalid_argument("remove_small_components: min_edges must be >= 0, got " +
                                std::to_string(min_edges));
  if (min_edges == 0 || mesh.faces.empty()) return {};
  const auto& x = mesh.vertices;
  double edge_sum = 0;
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) edge_sum += (x[f[i]] - x[f[(i + 1) % 3]]).norm();
  const double min_diagonal = min_edges * edge_sum / (3.0 * static_cast<double>(mesh.faces.size()));

  const Components c = components(mesh);
  detail::poll();
  const std::vector<Eigen::AlignedBox3d> box = detail::component_boxes(mesh, c);
  std::vector<char> small(x.size(), 0);
  for (std::size_t r = 0; r < x.size(); ++r)
    small[r] = c.faces[r] > 0 && static_cast<int>(r) != c.largest &&
               box[r].diagonal().norm() < min_diagonal;
  return remove_marked(mesh, c, small);
}

namespace {

// visit(v) for the smaller end v of every boundary edge (an edge of one face
// only). The edges are bucketed by their smaller end (a counting sort: linear,
// and polled), then sorted within their bucket of a few.
template <class Visit>
void for_each_boundary_edge(const TriangleMesh& mesh, Visit visit) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::size_t> first(nv + 1, 0);
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) ++first[std::min(f[i], f[(i + 1) % 3]) + 1];
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<int> other(first[nv]);
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      const auto [a, b] = std::minmax(f[i], f[(i + 1) % 3]);
      other[fill[a]++] = b;
    }
  detail::poll();
  for (std::size_t v = 0; v < nv; ++v) {
    detail::poll_every(v);
    const auto begin = other.begin() + first[v], end = other.begin() + first[v + 1];
    std::sort(begin, end);
    for (auto i = begin; i != end;) {
      auto j = i + 1;
      while (j != end && *j == *i) ++j;
      if (j - i == 1) visit(v);
      i = j;
    }
  }
}

}  // namespace

RemovedComponents remove_open_components(TriangleMesh& mesh) {
  if (mesh.faces.empty()) return {};
  const Components c = components(mesh);
  std::vector<char> open(mesh.vertices.size(), 0);
  for_each_boundary_edge(mesh, [&](std::size_t v) {
    if (c.root_of[v] != c.largest) open[c.root_of[v]] = 1;
  });
  return remove_marked(mesh, c, open);
}

std::size_t count_boundary_edges(const TriangleMesh& mesh) {
  std::size_t count = 0;
  for_each_boundary_edge(mesh, [&](std::size_t) { ++count; });
  return count;
}

RemovedComponents remove_unsupported_components(TriangleMesh& mesh,
                                                const std::vector<Vec3>& samples,
                                                int min_samples) {
  if (min_samples < 0)
    throw std::invalid_argument("remove_unsupported_components: min_samples must be >= 0");
  if (min_samples == 0 || mesh.faces.empty() || samples.empty()) return {};
  const Components c = components(mesh);
  // Only components but the largest can go: with one, the samples' queries are skipped.
  if (std::count_if(c.faces.begin(), c.faces.end(), [](int n) { return n > 0; }) <= 1) return {};
  // Each sample supports the component of the output vertex nearest to it.
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& f : mesh.faces)
    for (int v : f) used[v] = 1;
  std::vector<Vec3> vertices;
  std::vector<int> vertex_root;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (used[v]) {
      vertices.push_back(mesh.vertices[v]);
      vertex_root.push_back(c.root_of[v]);
    }
  detail::poll();
  const detail::NearestNeighbors tree(vertices);
  std::vector<int> nearest_root(samples.size());
  detail::polled_parallel_for(samples.size(), [&](std::size_t i) {
    nearest_root[i] = vertex_root[tree.query(samples[i], 1)[0]];
  });
  std::vector<double> support(mesh.vertices.size(), 0), area(mesh.vertices.size(), 0);
  for (int r : nearest_root) ++support[r];
  double total_area = 0;
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const double twice = (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a).norm();
    area[c.root_of[f[0]]] += 0.5 * twice;
    total_area += 0.5 * twice;
  }
  // Samples per unit area over the whole mesh, which a part of the shape has
  // about (more where the closed surface invents nothing).
  const double density = static_cast<double>(samples.size()) / total_area;
  std::vector<char> unsupported(mesh.vertices.size(), 0);
  for (std::size_t r = 0; r < mesh.vertices.size(); ++r)
    unsupported[r] = c.faces[r] > 0 && static_cast<int>(r) != c.largest &&
                     (support[r] < min_samples || support[r] < 0.1 * density * area[r]);
  return remove_marked(mesh, c, unsupported);
}

}  // namespace pdd
