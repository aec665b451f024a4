// One round of the optimizer, §3.3 "Linear Solver": minimize the frozen
// quadratic E(T) by CG from the current positions, guard the move, then
// rebuild the Delaunay triangulation and carry f over (Domain::move_vertices).
#include <pdd/errors.h>
#include <pdd/optimize.h>

#include "common/cancellation.h"
#include "common/nearest_neighbors.h"
#include "common/conjugate_gradient.h"
#include "common/parallel_kernels.h"
#include "optimize/energy_terms.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>

namespace pdd {
namespace {

void check(const OptimizerOptions& o) {
  auto fail = [](const std::string& what, double value) {
    throw InputError("optimizer: " + what + ", got " + std::to_string(value));
  };
  if (!(o.lambda_asap >= 0)) fail("lambda_asap must be >= 0", o.lambda_asap);
  if (!(o.lambda_mid_edge >= 0)) fail("lambda_mid_edge must be >= 0", o.lambda_mid_edge);
  if (!(o.damping_weight >= 0)) fail("damping_weight must be >= 0", o.damping_weight);
  if (!(o.boundary_band >= 0)) fail("boundary_band must be >= 0", o.boundary_band);
  if (!(o.cg_tolerance > 0)) fail("cg_tolerance must be > 0", o.cg_tolerance);
  if (o.cg_max_iterations < 1) fail("cg_max_iterations must be >= 1", o.cg_max_iterations);
  if (!(o.min_distance_ratio >= 0 && o.min_distance_ratio < 1))
    fail("min_distance_ratio must be in [0, 1)", o.min_distance_ratio);
}

// The inverse of each vertex's 3x3 diagonal block of A (its small eigenvalues
// raised to 1e-12 of its largest: a vertex moved by one term only has a
// rank-deficient block), identity for the fixed vertices: the block-Jacobi
// preconditioner. Scalar Jacobi is not invariant to rotations (the mid-edge
// term couples x, y and z through n n^T) and converges slowly where that term
// makes a block strongly anisotropic.
std::vector<Eigen::Matrix3d> block_jacobi(const optimize_detail::QuadraticAccumulator& A,
                                          const std::vector<bool>& fixed) {
  const int n = static_cast<int>(fixed.size());
  std::vector<Eigen::Matrix3d> inverse(n, Eigen::Matrix3d::Identity());
  tbb::parallel_for(0, n, [&](int v) {
    if (fixed[v]) return;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(A.diagonal_block(v));
    const Eigen::Vector3d lambda = eigen.eigenvalues();
    const double largest = lambda.cwiseAbs().maxCoeff();
    if (!(largest > 0)) return;
    const Eigen::Vector3d inv = lambda.cwiseMax(1e-12 * largest).cwiseInverse();
    inverse[v] = eigen.eigenvectors() * inv.asDiagonal() * eigen.eigenvectors().transpose();
  });
  return inverse;
}

// The minimizer of E over the free vertices: preconditioned CG on A x = b
// from x0 with the fixed vertices' coordinates held (their components of the
// residual and of every direction are zero), stopped at a residual relative
// to the initial one, which does not depend on where the domain sits.
Eigen::VectorXd minimize(const optimize_detail::BlockEnergy& energy, const Eigen::VectorXd& x0,
                         const OptimizerOptions& options, OptimizerReport& report) {
  const optimize_detail::QuadraticAccumulator& A = energy.quadratic;
  const Eigen::Index n = x0.size();
  const std::vector<Eigen::Matrix3d> inverse = block_jacobi(A, energy.fixed);
  auto mask = [&](Eigen::VectorXd& v) {
    detail::for_blocks(n / 3, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i)
        if (energy.fixed[i]) v.segment<3>(3 * i).setZero();
    });
  };
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z.resize(n);
    detail::for_blocks(n / 3, [&](Eigen::Index begin, Eigen::Index end) {
      for (Eigen::Index i = begin; i < end; ++i) z.segment<3>(3 * i) = inverse[i] * r.segment<3>(3 * i);
    });
  };
  Eigen::VectorXd x = x0, r, q;
  A.multiply(x, q);
  r = A.b - q;
  mask(r);
  const double r0 = std::sqrt(detail::deterministic_dot(r, r));
  if (r0 == 0) return x;
  const detail::PcgResult cg = detail::preconditioned_cg(
      [&](const Eigen::VectorXd& p, Eigen::VectorXd& Ap) {
        A.multiply(p, Ap);
        mask(Ap);
      },
      precondition, r, x, options.cg_tolerance, r0, options.cg_max_iterations);
  report.cg_iterations = cg.iterations;
  report.cg_residual = cg.residual;
  if (!x.allFinite()) throw SolverError("optimizer: the conjugate gradient diverged");
  return x;
}

// The shortest edge at each vertex (its nearest neighbour is one of its
// Delaunay neighbours).
std::vector<double> shortest_edges(const Domain& domain) {
  const auto& x = domain.vertices();
  std::vector<double> shortest(x.size(), std::numeric_limits<double>::infinity());
  const auto& tets = domain.tets();
  for (std::size_t k = 0; k < tets.size(); ++k) {
    const auto& t = tets[k];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double length = (x[t[i]] - x[t[j]]).norm();
        shortest[t[i]] = std::min(shortest[t[i]], length);
        shortest[t[j]] = std::min(shortest[t[j]], length);
      }
    detail::poll_every(k);  // the run's cancellation
  }
  return shortest;
}

// Moving vertices that would leave the domain or come closer to another
// vertex than min_distance_ratio times their shortest edge; `located`
// receives where the others' new positions fall in the domain.
std::vector<char> stray_vertices(const Domain& domain, const std::vector<Vec3>& positions,
                                 const std::vector<char>& moving, const std::vector<double>& shortest,
                                 double min_distance_ratio, std::vector<Location>& located) {
  const std::size_t n = positions.size();
  std::vector<char> stray(n, 0);
  const detail::NearestNeighbors nearest(positions);
  detail::poll();
  detail::polled_parallel_for(n, [&](std::size_t v) {
    if (!moving[v]) return;
    for (int u : nearest.query(positions[v], 2))
      if (u != static_cast<int>(v) &&
          (positions[u] - positions[v]).norm() < min_distance_ratio * shortest[v])
        stray[v] = 1;
  });
  // Point location only reads the triangulation (CGAL's walk keeps its
  // random state local), so the vertices are located concurrently.
  located.assign(n, Location());
  detail::polled_parallel_for(n, [&](std::size_t v) {
    if (!moving[v] || stray[v]) return;
    located[v] = domain.locate(positions[v], static_cast<int>(v));
    if (located[v].tet < 0) stray[v] = 1;
  });
  return stray;
}

// f at the new positions: interpolated in the tets they were located in for
// the moving vertices, unchanged for the others (§3.3, "Linear Solver").
std::vector<double> carried_values(const Domain& domain, const std::vector<char>& moving,
                                   const std::vector<Location>& located) {
  std::vector<double> f = domain.f();
  for (std::size_t v = 0; v < f.size(); ++v)
    if (moving[v]) f[v] = domain.interpolate(located[v], domain.f());
  return f;
}

// Moving vertices of the tets of `moved` that are flat: 6 vol <= 1e-12 l^3,
// l the longest edge (the operators of fem.h need 6 vol > 0 in floating point).
std::vector<char> collapsed_vertices(const Domain& moved, const std::vector<char>& moving) {
  const auto& x = moved.vertices();
  const auto& tets = moved.tets();
  std::vector<char> flat(tets.size(), 0);
  detail::polled_parallel_for(tets.size(), [&](std::size_t t) {
    const auto& v = tets[t];
    const Vec3 e1 = x[v[1]] - x[v[0]], e2 = x[v[2]] - x[v[0]], e3 = x[v[3]] - x[v[0]];
    const double l = std::max({e1.norm(), e2.norm(), e3.norm(), (e2 - e1).norm(),
                               (e3 - e1).norm(), (e3 - e2).norm()});
    flat[t] = !(e1.dot(e2.cross(e3)) > 1e-12 * l * l * l);
  });
  std::vector<char> collapsed(x.size(), 0);
  for (std::size_t t = 0; t < tets.size(); ++t)
    if (flat[t])
      for (int v : tets[t])
        if (moving[v]) collapsed[v] = 1;
  return collapsed;
}

}  // namespace

OptimizerReport optimize_domain(Domain& domain, const OptimizerOptions& options) {
  check(options);
  OptimizerReport report;
  if (domain.num_tets() == 0) return report;
  // E(T) is freed before the new domain is built (the round's peak of
  // memory), and built again, the same, if a collapsed tet sends moves back.
  // E(T) and its minimization read only the domain's arrays: its
  // triangulation is freed meanwhile, and restored for the guard's point
  // location.
  domain.release_triangulation();
  auto build_energy = [&] {
    return std::make_unique<optimize_detail::BlockEnergy>(
        optimize_detail::block_energy(domain, options));
  };
  auto energy = build_energy();
  detail::poll();  // the run's cancellation, between the steps of a round
  report.diameter = energy->diameter;
  report.crossing_tets = energy->crossing_tets;
  for (bool f : energy->fixed) report.fixed_vertices += f;

  const Eigen::VectorXd x0 = stacked_positions(domain);
  Eigen::VectorXd half_gradient;
  energy->quadratic.multiply(x0, half_gradient);
  detail::poll();
  report.energy_before =
      x0.dot(half_gradient) - 2.0 * energy->quadratic.b.dot(x0) + energy->quadratic.c;  // E(x0)
  half_gradient -= energy->quadratic.b;
  detail::poll();
  Eigen::VectorXd step = minimize(*energy, x0, options, report) - x0;

  // Guard. The triangulation is rebuilt as a Delaunay one after the move, so
  // no element of it can be inverted; what can go wrong is a vertex leaving
  // the domain (the hull, hence the boundary sphere, would change), a vertex
  // coming (nearly) onto another one, or a collapsed (flat) tet in the new
  // triangulation. The moves of the vertices involved are sent back, and E
  // must not rise along the remaining step: it is cut to the minimum of E on
  // its line if it would.
  const Eigen::Index n = x0.size() / 3;
  detail::poll();
  const std::vector<double> shortest = shortest_edges(domain);
  std::vector<char> rejected(n, 0);
  auto send_back = [&](const std::vector<char>& offenders) {
    bool any = false;
    for (Eigen::Index v = 0; v < n; ++v)
      if (offenders[v]) {
        step.segment<3>(3 * v).setZero();
        rejected[v] = 1;
        any = true;
      }
    return any;
  };
  double alpha = 1;
  double energy_change = 0;
  for (;;) {
    std::vector<Vec3> positions(n);
    std::vector<char> moving(n);
    for (Eigen::Index v = 0; v < n; ++v) {
      positions[v] = x0.segment<3>(3 * v) + alpha * step.segment<3>(3 * v);
      moving[v] = !step.segment<3>(3 * v).isZero(0);
    }
    std::vector<Location> located;
    detail::poll();
    if (send_back(stray_vertices(domain, positions, moving, shortest, options.min_distance_ratio,
                                 located)))
      continue;
    // E(x0 + a s) - E(x0) = a^2 s.As + 2 a s.(A x0 - b).
    if (!energy) energy = build_energy();
    Eigen::VectorXd A_step;
    energy->quadratic.multiply(step, A_step);
    const double curvature = step.dot(A_step);
    const double slope = step.dot(half_gradient);
    energy_change = alpha * alpha * curvature + 2 * alpha * slope;
    if (energy_change > 0) {
      const double line_minimum = slope < 0 && curvature > 0 ? -slope / curvature : 0.0;
      alpha = line_minimum > 0 && line_minimum < alpha ? line_minimum : 0.0;
      if (alpha > 0) continue;
      energy_change = 0;
      break;
    }
    if (std::find(moving.begin(), moving.end(), 1) == moving.end()) break;
    detail::poll();
    energy.reset();
    std::vector<double> carried = carried_values(domain, moving, located);
    // The old tets are not needed to build the new ones: freed first (the
    // round's peak of memory), built again only if moves are sent back; so
    // are the locations, and the positions go to the new domain.
    std::vector<Location>().swap(located);
    domain.release_tets();
    Domain moved = domain.moved(std::move(positions), std::move(carried));
    detail::poll();
    if (send_back(collapsed_vertices(moved, moving))) {
      domain.rebuild_tets();
      continue;
    }
    const std::vector<Vec3>& moved_to = moved.vertices();
    for (Eigen::Index v = 0; v < n; ++v)
      report.max_displacement =
          std::max(report.max_displacement,
                   (moved_to[v] - x0.segment<3>(3 * v)).norm() / report.diameter);
    domain = std::move(moved);
    break;
  }
  for (char r : rejected) report.rejected_moves += r;
  report.step_scale = alpha;
  report.energy_after = report.energy_before + energy_change;
  return report;
}

}  // namespace pdd
