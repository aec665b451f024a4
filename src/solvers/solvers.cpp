// The solver interface: names of the kinds and the factory.
#include <pdd/errors.h>
#include <pdd/solvers.h>

#include "solvers/kinds.h"

#include <algorithm>
#include <cctype>

namespace pdd {

ImplicitSolver::~ImplicitSolver() = default;

SolverKind parse_solver_kind(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "poisson") return SolverKind::kPoisson;
  if (lower == "ssd") return SolverKind::kSsd;
  if (lower == "spectral") return SolverKind::kSpectral;
  throw InputError("unknown solver \"" + name + "\" (expected poisson, ssd or spectral)");
}

std::string normals_requirement(SolverKind kind) {
  switch (kind) {
    case SolverKind::kPoisson: return "the Poisson solver needs oriented normals (Eq. 13)";
    case SolverKind::kSpectral: return "the spectral solver needs normals, oriented or not (Eq. 16)";
    case SolverKind::kSsd: break;
  }
  return "the SSD solver fits the gradient of f to oriented normals (Eq. 15)";
}

LinearMethod parse_linear_method(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "multigrid") return LinearMethod::kMultigrid;
  if (lower == "cholmod") return LinearMethod::kCholmod;
  throw InputError("unknown linear solver \"" + name + "\" (expected multigrid or cholmod)");
}

std::string to_string(LinearMethod method) {
  switch (method) {
    case LinearMethod::kMultigrid: return "multigrid";
    case LinearMethod::kCholmod: return "cholmod";
  }
  return "unknown";
}

std::string to_string(SolverKind kind) {
  switch (kind) {
    case SolverKind::kPoisson: return "poisson";
    case SolverKind::kSsd: return "ssd";
    case SolverKind::kSpectral: return "spectral";
  }
  return "unknown";
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
