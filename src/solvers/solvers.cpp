// The solver interface: names of the kinds and the factory.
#include <pdd/errors.h>
#include <pdd/solvers.h>

#include "common/enum_names.h"
#include "solvers/kinds.h"


namespace pdd {

ImplicitSolver::~ImplicitSolver() = default;

namespace {

constexpr EnumNames<SolverKind> kSolvers[] = {{SolverKind::kPoisson, "poisson"},
                                              {SolverKind::kSsd, "ssd"},
                                              {SolverKind::kSpectral, "spectral"}};
constexpr EnumNames<LinearMethod> kLinearMethods[] = {{LinearMethod::kMultigrid, "multigrid"},
                                                      {LinearMethod::kCholmod, "cholmod"}};

}  // namespace

SolverKind parse_solver_kind(const std::string& name) {
  return parse_enum(name, kSolvers, "solver");
}
std::string to_string(SolverKind kind) { return enum_name(kind, kSolvers); }

LinearMethod parse_linear_method(const std::string& name) {
  return parse_enum(name, kLinearMethods, "linear solver");
}
std::string to_string(LinearMethod method) { return enum_name(method, kLinearMethods); }

std::string normals_requirement(SolverKind kind) {
  switch (kind) {
    case SolverKind::kPoisson: return "the Poisson solver needs oriented normals (Eq. 13)";
    case SolverKind::kSpectral: return "the spectral solver needs normals, oriented or not (Eq. 16)";
    case SolverKind::kSsd: break;
  }
  return "the SSD solver fits the gradient of f to oriented normals (Eq. 15)";
}

std::unique_ptr<ImplicitSolver> make_solver(const SolverOptions& options) {
  switch (options.kind) {
    case SolverKind::kPoisson: return detail::make_poisson_solver(options.poisson, options.linear);
    case SolverKind::kSsd: return detail::make_ssd_solver(options.ssd, options.linear);
    case SolverKind::kSpectral:
      return detail::make_spectral_solver(options.spectral, options.linear);
  }
  throw std::invalid_argument("make_solver: unknown solver kind");
}

}  // namespace pdd
