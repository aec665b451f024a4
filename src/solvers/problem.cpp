#include "solvers/problem.h"

#include "common/cancellation.h"
#include "common/hilbert_order.h"
#include <pdd/errors.h>
#include <pdd/io.h>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace pdd::detail {
namespace {

// The mesh with its vertices renumbered along a Hilbert curve, and
// original[u], the index in `mesh` of vertex u.
std::unique_ptr<TetMesh> hilbert_ordered(const TetMesh& mesh, std::vector<int>& original) {
  const std::size_t n = mesh.vertices.size();
  original = hilbert_order(mesh.vertices);
  auto ordered = std::make_unique<TetMesh>();
  ordered->vertices.resize(n);
  std::vector<int> renumbered(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t u) {
    ordered->vertices[u] = mesh.vertices[original[u]];
    renumbered[original[u]] = static_cast<int>(u);
  });
  ordered->tets.resize(mesh.tets.size());
  tbb::parallel_for(std::size_t(0), mesh.tets.size(), [&](std::size_t t) {
    for (int i = 0; i < 4; ++i) ordered->tets[t][i] = renumbered[mesh.tets[t][i]];
  });
  return ordered;
}

}  // namespace

const std::vector<std::size_t>& SampleOrder::of(const std::vector<Vec3>& points) {
  // FNV-1a over the coordinates' bits, with the count.
  std::uint64_t key = 14695981039346656037ull ^ points.size();
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits;
      std::memcpy(&bits, &p[k], sizeof bits);
      key = (key ^ bits) * 1099511628211ull;
    }
  if (key != key_ || order_.size() != points.size()) {
    order_ = location_order(points);
    key_ = key;
  }
  return order_;
}

Problem make_problem(const Domain& domain, const PointSet& points, const std::string& solver,
                     const std::string& why_normals, const ProblemOptions& options) {
  if (points.size() == 0) throw InputError(solver + ": the point set is empty");
  require_normals(points, solver, why_normals);
  if (points.normals.size() != points.points.size())
    throw InputError(solver + ": " + std::to_string(points.normals.size()) + " normals for " +
                     std::to_string(points.points.size()) + " points");
  std::vector<Location> locations;
  try {
    locations = locate_points(domain, points.points,
                              options.order ? &options.order->of(points.points) : nullptr);
  } catch (const InputError& e) {
    throw InputError(solver + ": " + e.what());
  }
  if (options.release_triangulation) domain.release_triangulation();
  poll();
  // The locations name tets, whose order the renumbering keeps.
  std::vector<int> original;
  std::unique_ptr<TetMesh> ordered;
  if (options.spatial_order) ordered = hilbert_ordered(domain.mesh(), original);
  // (A braced list is evaluated in order: the mesh is bound before `ordered` moves.)
  Problem p{ordered ? *ordered : domain.mesh(), std::move(locations), {}, {}, 1, 0,
            std::move(ordered), std::move(original)};
  poll();
  if (options.phi == SamplingMatrix::kBuild) {
    sampling_matrix(p.mesh, p.locations).swap(p.Phi);  // Eigen 3.4's SparseMatrix: = would copy
    poll();
  }
  Eigen::AlignedBox3d box;
  for (const Vec3& x : points.points) box.extend(x);
  p.length = box.sizes().maxCoeff();
  if (!(p.length > 0)) throw InputError(solver + ": all points coincide");
  p.num_points = points.size();
  p.normals.reserve(points.size());
  for (const Vec3& n : points.normals) p.normals.push_back(n.normalized());
  return p;
}

double median_at_samples(const SparseMatrix& Phi, const Eigen::VectorXd& f) {
  Eigen::VectorXd values = Phi * f;
  const std::ptrdiff_t mid = values.size() / 2;
  std::nth_element(values.data(), values.data() + mid, values.data() + values.size());
  return values[mid];
}

std::vector<int> outer_vertices(const Domain& domain) {
  std::vector<int> out;
  for (int v = 0; v < static_cast<int>(domain.num_vertices()); ++v)
    if (domain.on_boundary_sphere(v)) out.push_back(v);
  if (!out.empty()) return out;
  std::vector<char> hull(domain.num_vertices(), 0);
  for_each_hull_face(domain, [&](int a, int b, int c) { hull[a] = hull[b] = hull[c] = 1; });
  for (int v = 0; v < static_cast<int>(hull.size()); ++v)
    if (hull[v]) out.push_back(v);
  return out;
}

Eigen::VectorXd Problem::warm_start(const std::vector<double>* values) const {
  if (values == nullptr) return {};
  const std::size_t n = mesh.vertices.size();
  if (values->size() != n)
    throw std::invalid_argument("solver: the warm start has " + std::to_string(values->size()) +
                                " values for " + std::to_string(n) + " vertices");
  Eigen::VectorXd f(static_cast<Eigen::Index>(n));
  for (std::size_t u = 0; u < n; ++u)
    f[static_cast<Eigen::Index>(u)] = (*values)[original.empty() ? u : original[u]];
  return f;
}

std::vector<double> Problem::domain_values(const Eigen::VectorXd& f) const {
  std::vector<double> values(static_cast<std::size_t>(f.size()));
  for (std::size_t u = 0; u < values.size(); ++u)
    values[original.empty() ? u : original[u]] = f[static_cast<Eigen::Index>(u)];
  return values;
}

}  // namespace pdd::detail
