// E(T), Eq. (1), frozen for one round: a quadratic in the 3|V| coordinates.
#include <pdd/isofacet.h>
#include <pdd/optimize.h>

#include "common/cancellation.h"
#include "common/parallel_kernels.h"
#include "optimize/energy_terms.h"

#include <cmath>

namespace pdd {

// A is symmetric: its products run on all cores (Eigen's column-major
// product is serial, 0.5 s at 1.6M vertices).
double DomainEnergy::value(const Eigen::VectorXd& x) const {
  Eigen::VectorXd Ax;
  detail::symmetric_product(A, x, Ax);
  return x.dot(Ax) - 2.0 * b.dot(x) + c;
}

Eigen::VectorXd DomainEnergy::gradient(const Eigen::VectorXd& x) const {
  Eigen::VectorXd Ax;
  detail::symmetric_product(A, x, Ax);
  return 2.0 * (Ax - b);
}

Eigen::VectorXd stacked_positions(const Domain& domain) {
  const auto& x = domain.vertices();
  Eigen::VectorXd out(3 * x.size());
  for (std::size_t i = 0; i < x.size(); ++i) out.segment<3>(3 * i) = x[i];
  return out;
}

namespace optimize_detail {

BlockEnergy block_energy(const Domain& domain, const OptimizerOptions& options) {
  BlockEnergy energy(domain);
  QuadraticAccumulator& q = energy.quadratic;
  energy.diameter = triangulation_diameter(domain);
  energy.fixed = boundary_vertices(domain, options.boundary_band * energy.diameter);
  detail::poll();  // the run's cancellation, between the steps

  for (std::size_t t = 0; t < domain.num_tets(); ++t)
    energy.crossing_tets += crosses_isovalue(domain.mesh(), domain.f(), static_cast<int>(t));

  // Lengths are measured in units of r(T), so that E is dimensionless and
  // the minimizer invariant to rigid motion and uniform scaling: w_a =
  // vol(t) / r^3 and w_m = area(a_t) / r^2 as in §3.3, E_a, E_m and E_d
  // divided by r^2. The paper's w_d = 100 / r(T) would scale unlike the other
  // two terms; it becomes w_d = 100 in these units.
  const double r = energy.diameter;
  if (r > 0) {
    if (options.asap && options.lambda_asap > 0)
      add_asap_term(domain, options.lambda_asap / std::pow(r, 5), q);
    detail::poll();
    if (options.mid_edge && options.lambda_mid_edge > 0)
      add_mid_edge_term(domain, options.lambda_mid_edge / std::pow(r, 4), q);
    detail::poll();
    if (options.damping && options.damping_weight > 0)
      add_damping_term(domain, energy.fixed, options.damping_weight / (r * r), q);
  }
  q.finish_terms();
  detail::poll();
  return energy;
}

}  // namespace optimize_detail

DomainEnergy domain_energy(const Domain& domain, const OptimizerOptions& options) {
  optimize_detail::BlockEnergy blocks = optimize_detail::block_energy(domain, options);
  DomainEnergy energy;
  blocks.quadratic.matrix().swap(energy.A);  // Eigen 3.4's SparseMatrix has no move: = would copy
  energy.b = std::move(blocks.quadratic.b);
  energy.c = blocks.quadratic.c;
  energy.fixed = std::move(blocks.fixed);
  energy.diameter = blocks.diameter;
  energy.crossing_tets = blocks.crossing_tets;
  return energy;
}

}  // namespace pdd
