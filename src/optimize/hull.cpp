// The boundary ∂T of the domain (the faces of its convex hull), its diameter
// r(T) and the vertices held by the boundary constraint of §3.3.
#include <pdd/optimize.h>

#include "optimize/energy_terms.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdd {
namespace optimize_detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_point(const Vec3& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); }

std::vector<int> hull_vertices(const Domain& domain) {
  std::vector<bool> on_hull(domain.num_vertices(), false);
  for (const auto& f : hull_faces(domain))
    for (int v : f) on_hull[v] = true;
  std::vector<int> out;
  for (std::size_t v = 0; v < on_hull.size(); ++v)
    if (on_hull[v]) out.push_back(static_cast<int>(v));
  return out;
}

}  // namespace

std::vector<std::array<int, 3>> hull_faces(const Domain& domain) {
  std::vector<std::array<int, 3>> faces;
  const auto& tets = domain.tets();
  const auto& neighbors = domain.tet_neighbors();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (int i = 0; i < 4; ++i)
      if (neighbors[t][i] < 0)
        faces.push_back({tets[t][(i + 1) % 4], tets[t][(i + 2) % 4], tets[t][(i + 3) % 4]});
    detail::poll_every(t);  // the run's cancellation
  }
  return faces;
}

std::vector<bool> boundary_vertices(const Domain& domain, double band) {
  const std::size_t n = domain.num_vertices();
  const auto& x = domain.vertices();
  std::vector<bool> fixed(n, false);
  const auto faces = hull_faces(domain);
  for (const auto& f : faces)
    for (int v : f) fixed[v] = true;
  for (std::size_t v = 0; v < n; ++v)
    if (domain.on_boundary_sphere(static_cast<int>(v))) fixed[v] = true;
  if (!(band > 0) || faces.empty()) return fixed;

  // Distance to ∂T through an AABB tree of the hull triangles (CGAL).
  std::vector<Triangle> triangles;
  triangles.reserve(faces.size());
  for (const auto& f : faces)
    triangles.emplace_back(to_point(x[f[0]]), to_point(x[f[1]]), to_point(x[f[2]]));
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  // The hull, convex, holds the ball about an inner point c whose radius is
  // the distance from c to the nearest face plane: a vertex deeper than
  // `band` inside that ball needs no query (nearly all of them).
  // c is inside when it lies on the side of every face plane where the hull
  // vertices' centroid lies (read off the arrays: the triangulation may be
  // released). Where rounding could tip a side, c is within rounding of a
  // face, inner is about 0 and every vertex is queried: either way is right.
  const Vec3 c = domain.center();
  Vec3 centroid = Vec3::Zero();
  for (const auto& f : faces) centroid += (x[f[0]] + x[f[1]] + x[f[2]]) / 3.0;
  centroid /= static_cast<double>(faces.size());
  double inner = std::numeric_limits<double>::infinity();
  for (const auto& f : faces) {
    const Vec3 normal = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    const double side = normal.dot(c - x[f[0]]);
    if (side * normal.dot(centroid - x[f[0]]) < 0) {
      inner = 0;
      break;
    }
    inner = std::min(inner, std::abs(side) / normal.norm());
  }
  std::vector<char> near(n, 0);  // written concurrently: no std::vector<bool>
  const double band2 = band * band;
  detail::polled_parallel_for(n, [&](std::size_t v) {
    if (!fixed[v] && (x[v] - c).norm() > inner - band)
      near[v] = tree.squared_distance(to_point(x[v])) < band2;
  });
  for (std::size_t v = 0; v < n; ++v)
    if (near[v]) fixed[v] = true;
  return fixed;
}

}  // namespace optimize_detail

double triangulation_diameter(const Domain& domain) {
  // The farthest pair of a point set is a pair of hull vertices; the hull is
  // small next to the domain, so all its pairs are compared.
  const std::vector<int> hull = optimize_detail::hull_vertices(domain);
  const auto& x = domain.vertices();
  const double d2 = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, hull.size()), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double best) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          for (std::size_t j = i + 1; j < hull.size(); ++j)
            best = std::max(best, (x[hull[i]] - x[hull[j]]).squaredNorm());
        return best;
      },
      [](double a, double b) { return std::max(a, b); });
  return std::sqrt(d2);
}

}  // namespace pdd
