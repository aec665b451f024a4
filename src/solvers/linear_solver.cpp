#include "solvers/linear_solver.h"

#include "common/parallel_kernels.h"
#include "solvers/hierarchy.h"
#include "solvers/multigrid.h"
#include "solvers/problem.h"

#include <pdd/errors.h>

#include <Eigen/CholmodSupport>

#include <sstream>

namespace pdd::detail {
namespace {

using Cholmod = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;

[[noreturn]] void fail(const std::string& what, double residual) {
  std::ostringstream msg;
  msg << what << " (relative residual " << residual << ")";
  throw SolverError(msg.str());
}

// Galerkin correction of a warm start x in span{x, 1}: the previous iterate
// typically differs from the solution by a scale and a constant (a median
// shift, another solver's normalization), the smoothest modes.
void correct_warm_start(const SymmetricProduct<double>& A, const Eigen::VectorXd& b,
                        Eigen::VectorXd& x) {
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(b.size());
  Eigen::VectorXd Ax, A1;
  A(x, Ax);
  A(ones, A1);
  Eigen::Matrix2d K;
  K << deterministic_dot(x, Ax), deterministic_dot(x, A1), deterministic_dot(ones, Ax),
      deterministic_dot(ones, A1);
  const Eigen::Vector2d ac =
      K.ldlt().solve(Eigen::Vector2d(deterministic_dot(x, b), deterministic_dot(ones, b)));
  if (ac.allFinite()) x = ac[0] * x + ac[1] * ones;
}

}  // namespace

struct LinearSolver::Impl {
  LinearSolverOptions options;
  SymmetricProduct<double> A;  // with the caller's matrix, see compute()
  bool direct = false;
  Cholmod cholmod;
  ProgressiveHierarchy hierarchy;
  Multigrid multigrid;

  explicit Impl(const LinearSolverOptions& o)
      : options(o),
        hierarchy(o.coarsening_ratio, o.coarsest_size) {
    cholmod_common& common = cholmod.cholmod();
    common.print = 0;  // failures are reported as SolverError, not printed
    // Nested dissection (METIS) only: CHOLMOD's default also tries AMD and
    // keeps the better, and on the SSD matrices METIS always won
    // (docs/benchmarks.md), so the AMD pass was time spent for nothing.
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_METIS;
  }
};

namespace {

const LinearSolverOptions& checked(const LinearSolverOptions& o) {
  if (!(o.cg_tolerance > 0) || o.cg_max_iterations < 1 || o.smoothing_degree < 1 ||
      o.finest_smoothing_degree < 1 ||
      !(o.coarsening_ratio >= 1.3) || o.coarsest_size < 4 || !(o.block_coupling > 0))
    throw InputError(
        "linear solver: the CG tolerance must be > 0, its iterations >= 1, the smoothing degrees "
        ">= 1, the coarsening ratio >= 1.3, the coarsest level >= 4 vertices and the block "
        "coupling > 0");
  return o;
}

}  // namespace

LinearSolver::LinearSolver(const LinearSolverOptions& options)
    : impl_(std::make_unique<Impl>(checked(options))) {}

LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

bool LinearSolver::iterative(std::size_t n) const {
  return impl_->options.method != LinearMethod::kCholmod && n >= impl_->options.direct_below;
}

void LinearSolver::compute(const SparseMatrix& A, const std::vector<Vec3>& vertices,
                           Stored stored, const std::vector<int>& original) {
  const auto start = Clock::now();
  Impl& d = *impl_;
  if (static_cast<std::size_t>(A.rows()) != vertices.size())
    throw std::invalid_argument("LinearSolver: one unknown per vertex is required");
  d.A = SymmetricProduct<double>(A, stored == Stored::kLower);
  d.direct = !iterative(vertices.size());
  if (d.direct) {
    d.cholmod.compute(A);
    if (d.cholmod.info() != Eigen::Success)
      throw SolverError("CHOLMOD: the system matrix is not positive definite (" +
                        std::to_string(A.rows()) + " unknowns)");
    levels_ = 1;
  } else {
    MultigridOptions mg;
    mg.smoothing_degree = d.options.smoothing_degree;
    mg.finest_smoothing_degree = d.options.finest_smoothing_degree;
    mg.coarsest_size = d.options.coarsest_size;
    mg.block_coupling = d.options.block_coupling;
    d.multigrid.setup(d.A, d.hierarchy.levels_for(vertices, original), mg);
    levels_ = static_cast<int>(d.multigrid.num_levels());
  }
  // The hierarchy remembers every domain, solved directly or not.
  if (d.direct) d.hierarchy.remember(vertices.size());
  method_ = d.direct ? "cholmod" : "cg+multigrid";
  setup_seconds_ = seconds_since(start);
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& d = *impl_;
  const double b_norm = b.norm();
  iterations_ = 0;
  if (b_norm == 0) {
    x.setZero(b.size());
    residual_ = 0;
    return;
  }
  if (d.direct) {
    x = d.cholmod.solve(b);
  } else {
    const bool warm = x.size() == b.size() && x.allFinite() && x.squaredNorm() > 0;
    if (warm)
      correct_warm_start(d.A, b, x);
    else
      x.setZero(b.size());
    const CgResult cg = multigrid_cg(d.A, d.multigrid, b, x, d.options.cg_tolerance,
                                     d.options.cg_max_iterations);
    iterations_ = cg.iterations;
    residual_ = cg.residual;  // recomputed from x by multigrid_cg
    if (!cg.converged)
      fail("multigrid conjugate gradients did not converge in " + std::to_string(cg.iterations) +
               " iterations",
           cg.residual);
  }
  if (d.direct) {
    Eigen::VectorXd Ax;
    d.A(x, Ax);
    residual_ = (Ax - b).norm() / b_norm;
  }
  if (!x.allFinite()) fail("linear solve produced non-finite values", residual_);
  if (d.direct && residual_ > d.options.max_residual) fail("CHOLMOD solve is inaccurate", residual_);
}

void LinearSolver::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (impl_->direct)
    z = impl_->cholmod.solve(r);
  else
    impl_->multigrid.precondition(r, z);
}

void LinearSolver::release() {
  impl_->multigrid.clear();
  impl_->A = SymmetricProduct<double>();
}

void LinearSolver::report(SolverStats& stats) const {
  stats.method = method_;
  stats.iterations = iterations_;
  stats.residual = residual_;
  stats.factorize_seconds = setup_seconds_;
  stats.levels = levels_;
}

}  // namespace pdd::detail

