// Metro-style two-sided surface distances: area-uniform samples on each mesh,
// exact point-to-triangle distances to the other mesh through a CGAL AABB tree.
#include <pdd/compare.h>
#include <pdd/errors.h>
#include <pdd/quality.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "common/hilbert_order.h"
#include "metrics/elements.h"

namespace pdd {

namespace {

// Exact predicates are not needed: the distances are measured, not decided.
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

double face_area(const TriangleMesh& mesh, const std::array<int, 3>& f) {
  const Vec3& a = mesh.vertices[f[0]];
  return 0.5 * (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a).norm();
}

// Throws std::invalid_argument, starting with `what`, unless the mesh's faces
// index its vertices and cover a positive area.
void check_surface(const TriangleMesh& mesh, const std::string& what) {
  if (!(surface_area(mesh) > 0))
    throw std::invalid_argument(what + " has no area (" + std::to_string(mesh.faces.size()) +
                                " faces)");
}

// The distances from `samples` to the faces of `target`, then their
// statistics. The queries run in parallel into one slot per sample and are
// summed in sample order, so that the result does not depend on scheduling.
OneSidedDistance one_sided(const std::vector<Vec3>& samples, const TriangleMesh& target,
                           double threshold) {
  std::vector<Triangle> triangles;
  triangles.reserve(target.faces.size());
  auto point = [](const Vec3& v) { return Point(v.x(), v.y(), v.z()); };
  for (const auto& f : target.faces)
    triangles.emplace_back(point(target.vertices[f[0]]), point(target.vertices[f[1]]),
                           point(target.vertices[f[2]]));
  Tree tree(triangles.begin(), triangles.end());
  // Build the tree and its search hints now: concurrent queries then only read.
  tree.build();
  tree.accelerate_distance_queries();

  // Queries in Hilbert order: consecutive queries visit the same parts of the
  // tree, which then stay in cache.
  std::vector<Point> points;
  points.reserve(samples.size());
  for (const Vec3& s : samples) points.push_back(point(s));
  const std::vector<int> order = detail::hilbert_order(samples);

  std::vector<double> squared(samples.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k)
                        squared[order[k]] = tree.squared_distance(points[order[k]]);
                    });

  OneSidedDistance d;
  d.samples = samples.size();
  double sum = 0, sum_squared = 0;
  std::size_t within = 0;
  for (const double s : squared) {
    const double distance = std::sqrt(s);
    d.max = std::max(d.max, distance);
    sum += distance;
    sum_squared += s;
    if (distance <= threshold) ++within;
  }
  const double n = static_cast<double>(samples.size());
  d.mean = sum / n;
  d.rms = std::sqrt(sum_squared / n);
  d.within_threshold = static_cast<double>(within) / n;
  return d;
}

double bounding_box_diagonal(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& f : mesh.faces)
    for (const int v : f) box.extend(mesh.vertices[v]);
  return box.diagonal().norm();
}

}  // namespace

double surface_area(const TriangleMesh& mesh) {
  detail::check_indices(mesh.faces, mesh.vertices.size(), "face");
  double area = 0;
  for (const auto& f : mesh.faces) area += face_area(mesh, f);
  return area;
}

void require_area(const TriangleMesh& mesh, const std::string& source) {
  require_measurable(mesh, source);
  if (!(surface_area(mesh) > 0))
    throw InputError(source + ": the mesh has no area (all " + std::to_string(mesh.faces.size()) +
                     " faces are degenerate)");
}

// Hand-written rather than CGAL's Random_points_in_triangles_3 so that the
// draws come from std::mt19937_64 with pdd's 64-bit seeds, without copying
// the mesh into CGAL triangles.
std::vector<Vec3> sample_surface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
  check_surface(mesh, "sample_surface: the mesh");
  // cumulative[i]: the area of faces 0..i; a uniform draw in [0, total) picks a
  // face with probability proportional to its area (faces of zero area never).
  std::vector<double> cumulative(mesh.faces.size());
  double total = 0;
  for (std::size_t i = 0; i < mesh.faces.size(); ++i)
    cumulative[i] = total += face_area(mesh, mesh.faces[i]);

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Vec3> samples;
  samples.reserve(count);
  while (samples.size() < count) {
    const double at = uniform(rng) * total;
    const std::size_t face =
        std::min<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), at) -
                                  cumulative.begin(),
                              mesh.faces.size() - 1);
    const auto& f = mesh.faces[face];
    // Uniform in the triangle: with s = sqrt(r1), (1 - s, s (1 - r2), s r2) are
    // barycentric coordinates of density proportional to area.
    const double s = std::sqrt(uniform(rng)), r2 = uniform(rng);
    samples.push_back((1 - s) * mesh.vertices[f[0]] + s * (1 - r2) * mesh.vertices[f[1]] +
                      s * r2 * mesh.vertices[f[2]]);
  }
  return samples;
}

SurfaceDistance compare_surfaces(const TriangleMesh& a, const TriangleMesh& b,
                                 const CompareOptions& options) {
  if (options.samples == 0 || options.samples > CompareOptions::kMaxSamples)
    throw std::invalid_argument("compare: samples must be from 1 to " +
                                std::to_string(CompareOptions::kMaxSamples) + ", got " +
                                std::to_string(options.samples));
  if (!(options.fscore_threshold >= 0))
    throw std::invalid_argument("compare: the F-score threshold must be non-negative");
  check_surface(a, "compare: mesh A");
  check_surface(b, "compare: mesh B");

  SurfaceDistance d;
  d.diagonal = bounding_box_diagonal(b);
  d.threshold = options.fscore_threshold * d.diagonal;
  d.a_to_b = one_sided(sample_surface(a, options.samples, options.seed), b, d.threshold);
  d.b_to_a = one_sided(sample_surface(b, options.samples, options.seed + 1), a, d.threshold);
  d.hausdorff = std::max(d.a_to_b.max, d.b_to_a.max);
  d.chamfer_l1 = 0.5 * (d.a_to_b.mean + d.b_to_a.mean);
  d.precision = d.a_to_b.within_threshold;
  d.recall = d.b_to_a.within_threshold;
  const double sum = d.precision + d.recall;
  d.fscore = sum > 0 ? 2 * d.precision * d.recall / sum : 0.0;
  return d;
}

}  // namespace pdd
