#include "solvers/linear_solver.h"

#include "solvers/problem.h"

#include <pdd/errors.h>

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <sstream>

namespace pdd::detail {
namespace {

using Cholmod = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
// Eigen's AMD ordering, of the pattern given to LinearSolver::compute when
// there is one (OrderingPattern below), else of the matrix itself. Eigen's
// incomplete Cholesky default-constructs its ordering, so the pattern comes
// through a thread-local pointer set for the time of one analysis.
struct PatternAmdOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  static thread_local const SparseMatrix* pattern;
  template <class MatrixType>
  void operator()(const MatrixType& matrix, PermutationType& permutation) const {
    Eigen::AMDOrdering<int> amd;
    if (pattern != nullptr)
      amd(*pattern, permutation);
    else
      amd(matrix, permutation);
  }
};
thread_local const SparseMatrix* PatternAmdOrdering::pattern = nullptr;

// Sets PatternAmdOrdering::pattern for its scope.
class OrderingPattern {
 public:
  explicit OrderingPattern(const SparseMatrix* pattern) { PatternAmdOrdering::pattern = pattern; }
  ~OrderingPattern() { PatternAmdOrdering::pattern = nullptr; }
  OrderingPattern(const OrderingPattern&) = delete;
  OrderingPattern& operator=(const OrderingPattern&) = delete;
};

using IncompleteCholesky = Eigen::IncompleteCholesky<double, Eigen::Lower, PatternAmdOrdering>;
using CgIncompleteCholesky =
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, IncompleteCholesky>;
using CgJacobi = Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                                          Eigen::DiagonalPreconditioner<double>>;

// The sparsity pattern of a compressed matrix, to tell whether the next
// one can reuse CHOLMOD's symbolic analysis.
struct Pattern {
  std::vector<int> outer, inner;
  explicit Pattern(const SparseMatrix& a = SparseMatrix())
      : outer(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1),
        inner(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros()) {}
  bool matches(const SparseMatrix& a) const {
    return static_cast<Eigen::Index>(outer.size()) == a.outerSize() + 1 &&
           static_cast<Eigen::Index>(inner.size()) == a.nonZeros() &&
           std::equal(outer.begin(), outer.end(), a.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), a.innerIndexPtr());
  }
};

[[noreturn]] void fail(const std::string& what, double residual) {
  std::ostringstream msg;
  msg << what << " (relative residual " << residual << ")";
  throw SolverError(msg.str());
}

// Galerkin correction of a warm start x in span{x, 1}: the previous iterate
// typically differs from the solution by a scale and a constant (a median
// shift, another solver's normalization), the smoothest modes and so the
// slowest for CG.
void correct_warm_start(const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(b.size());
  const Eigen::VectorXd Ax = A * x, A1 = A * ones;
  Eigen::Matrix2d K;
  K << x.dot(Ax), x.dot(A1), ones.dot(Ax), ones.dot(A1);
  const Eigen::Vector2d ac = K.ldlt().solve(Eigen::Vector2d(x.dot(b), ones.dot(b)));
  if (ac.allFinite()) x = ac[0] * x + ac[1] * ones;
}

// A + shift diag(|a_j|), |a_j| the norm of column j. Eigen's incomplete
// Cholesky factors S A S, S = diag(1 / sqrt|a_j|) (Lin and More), so this
// adds about `shift` to the diagonal of the matrix it factors.
SparseMatrix shifted_for_ic(const SparseMatrix& A, double shift) {
  SparseMatrix shifted = A;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    shifted.coeffRef(j, j) += shift * A.col(j).norm();
  return shifted;
}

// The shift Eigen's incomplete Cholesky of M added to its scaled diagonal
// after breakdowns (a pivot <= 0; each one restarts the factorization with
// twice the shift), 0 if there were none. Read off the first pivot, which
// no column updates: L_00^2 = (S P M P^T S)_00 + shift.
double breakdown_shift(const IncompleteCholesky& ic, const SparseMatrix& M) {
  Eigen::Index first = 0;  // the column of M that the ordering puts first
  const auto& order = ic.permutationP().indices();
  while (order.size() > 0 && order[first] != 0) ++first;
  const double pivot = ic.matrixL().coeff(0, 0);
  const double scale = ic.scalingS()[0];
  return std::max(0.0, pivot * pivot - scale * scale * M.coeff(first, first));
}

template <class Cg>
int run_cg(Cg& cg, const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (x.size() == b.size() && x.allFinite() && x.squaredNorm() > 0) {
    correct_warm_start(A, b, x);
    x = cg.solveWithGuess(b, x);
  } else {
    x = cg.solve(b);
  }
  return static_cast<int>(cg.iterations());
}

}  // namespace

struct LinearSolver::Impl {
  LinearSolverOptions options;
  const SparseMatrix* A = nullptr;  // the caller's, see compute()
  const SparseMatrix* ordering_pattern = nullptr;  // the caller's too, or none
  Pattern analyzed_pattern;         // CHOLMOD: the pattern of the analysis
  Cholmod cholmod;
  CgJacobi cg_jacobi;
  CgIncompleteCholesky cg_ic;
  bool analyzed = false;
  bool factorized = false;     // CHOLMOD holds the factor of *A
  bool preconditioned = false;  // the CG preconditioner is that of *A
  double ic_shift = 0;          // of the last preconditioner, see precondition()

  void precondition(Preconditioner preconditioner) {
    if (preconditioner == Preconditioner::kJacobi) {
      cg_jacobi.compute(*A);
    } else {
      // CG iterates with A; the preconditioner factors A shifted by the
      // smallest shift that worked so far, so that the systems of the next
      // iterations, much alike, break down less often.
      const SparseMatrix shifted = shifted_for_ic(*A, ic_shift);
      {
        const OrderingPattern ordering(ordering_pattern);
        cg_ic.analyzePattern(*A);
      }
      cg_ic.preconditioner().factorize(shifted);
      if (cg_ic.preconditioner().info() != Eigen::Success)
        throw SolverError("incomplete Cholesky preconditioner failed (" +
                          std::to_string(A->rows()) + " unknowns)");
      const double added = breakdown_shift(cg_ic.preconditioner(), shifted);
      if (added > 1e-9) ic_shift += added;
    }
    preconditioned = true;
  }

  // CHOLMOD's factor of *A, reusing the analysis while the pattern stays.
  // Returns whether the analysis was reused.
  bool factorize() {
    const bool reuse = analyzed && analyzed_pattern.matches(*A);
    if (!reuse) {
      cholmod.analyzePattern(*A);
      analyzed_pattern = Pattern(*A);
    }
    analyzed = true;
    cholmod.factorize(*A);
    if (cholmod.info() != Eigen::Success) {
      analyzed = false;
      throw SolverError("CHOLMOD: the system matrix is not positive definite (" +
                        std::to_string(A->rows()) + " unknowns)");
    }
    factorized = true;
    return reuse;
  }
};

LinearSolver::LinearSolver(const LinearSolverOptions& options, const LinearRoute& route)
    : impl_(std::make_unique<Impl>()), route_(route) {
  if (route.method == LinearMethod::kAuto || route.preconditioner == Preconditioner::kAuto)
    throw std::invalid_argument("LinearSolver: the route must be resolved (not kAuto)");
  if (!(options.ic_shift >= 0))
    throw InputError("linear solver: ic_shift must be >= 0, got " + std::to_string(options.ic_shift));
  impl_->options = options;
  impl_->ic_shift = options.ic_shift;
  cholmod_common& common = impl_->cholmod.cholmod();
  common.print = 0;  // failures are reported as SolverError, not printed
  // Nested dissection (METIS) only: CHOLMOD's default also tries AMD first and
  // keeps the better, and on the SSD matrices of the pipeline METIS always
  // won (28.5M against 42M entries in L at 39k unknowns), so the AMD pass was
  // 0.2 s per analysis spent for nothing (docs/benchmarks.md).
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_METIS;
  const int cg_iterations =
      route.cholmod_after > 0 ? route.cholmod_after : options.cg_max_iterations;
  impl_->cg_jacobi.setTolerance(options.cg_tolerance);
  impl_->cg_jacobi.setMaxIterations(cg_iterations);
  impl_->cg_ic.setTolerance(options.cg_tolerance);
  impl_->cg_ic.setMaxIterations(cg_iterations);
}

LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::compute(const SparseMatrix& A, const SparseMatrix* ordering_pattern) {
  const auto start = Clock::now();
  Impl& d = *impl_;
  d.A = &A;
  d.ordering_pattern = ordering_pattern;
  d.factorized = false;
  d.preconditioned = false;
  reused_analysis_ = false;
  factorize_seconds_in_solves_ = 0;
  // With a CHOLMOD fallback, neither is built before a solve says which one
  // it needs (Lanczos' inner solves, without a warm start, need no CG).
  if (route_.method == LinearMethod::kCholmod)
    reused_analysis_ = d.factorize();
  else if (route_.cholmod_after == 0)
    d.precondition(route_.preconditioner);
  factorize_seconds_ = seconds_since(start);
}

void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& d = *impl_;
  const double b_norm = b.norm();
  iterations_ = 0;
  ic_shift_ = 0;
  if (b_norm == 0) {
    x.setZero(b.size());
    residual_ = 0;
    return;
  }
  const std::string cg_name =
      route_.preconditioner == Preconditioner::kJacobi ? "cg+jacobi" : "cg+ic";
  const bool warm = x.size() == b.size() && x.allFinite() && x.squaredNorm() > 0;
  bool direct = route_.method == LinearMethod::kCholmod || (route_.cholmod_after > 0 && !warm);
  method_ = direct ? "cholmod" : cg_name;
  // Time spent preparing for this solve rather than in it.
  auto prepare = [&](auto&& step) {
    const auto start = Clock::now();
    step();
    factorize_seconds_in_solves_ += seconds_since(start);
    factorize_seconds_ += seconds_since(start);
  };
  if (!direct) {
    if (!d.preconditioned) prepare([&] { d.precondition(route_.preconditioner); });
    bool converged;
    if (route_.preconditioner == Preconditioner::kJacobi) {
      iterations_ = run_cg(d.cg_jacobi, *d.A, b, x);
      converged = d.cg_jacobi.info() == Eigen::Success;
    } else {
      iterations_ = run_cg(d.cg_ic, *d.A, b, x);
      converged = d.cg_ic.info() == Eigen::Success;
      ic_shift_ = d.ic_shift;
    }
    if (!converged && route_.cholmod_after > 0) {
      direct = true;
      method_ = cg_name + ", then cholmod";
    } else if (!converged) {
      fail("conjugate gradients did not converge in " + std::to_string(iterations_) +
               " iterations",
           (*d.A * x - b).norm() / b_norm);
    }
  }
  if (direct) {
    if (!d.factorized) prepare([&] { reused_analysis_ = d.factorize(); });
    x = d.cholmod.solve(b);
  }
  residual_ = (*d.A * x - b).norm() / b_norm;
  if (!x.allFinite()) fail("linear solve produced non-finite values", residual_);
  if (direct && residual_ > d.options.max_residual) fail("CHOLMOD solve is inaccurate", residual_);
}

}  // namespace pdd::detail
