// Table 2's conditioning measure: CG iterations on a Hessian-dominated SSD system.
#include <pdd/solvers.h>

#include <Eigen/IterativeLinearSolvers>

#include <chrono>

namespace pdd {

ConditioningProbe ssd_conditioning_probe(const Domain& domain, const PointSet& points) {
  SsdOptions smooth;
  smooth.alpha = 1;
  smooth.beta = 1;
  smooth.gamma = 0.1;
  const LinearSystem system = ssd_system(domain, points, smooth);
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(1e-10);
  cg.setMaxIterations(1000000);
  const auto start = std::chrono::steady_clock::now();
  cg.compute(system.A);
  const Eigen::VectorXd f = cg.solve(system.b);
  ConditioningProbe probe;
  probe.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  probe.iterations = static_cast<long>(cg.iterations());
  probe.residual = (system.A * f - system.b).norm() / system.b.norm();
  probe.converged = cg.info() == Eigen::Success;
  return probe;
}

}  // namespace pdd
