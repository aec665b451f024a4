// Private to src/solvers: one factory per solver, called by make_solver.
#pragma once

#include <pdd/solvers.h>

#include <memory>

namespace pdd::detail {

std::unique_ptr<ImplicitSolver> make_poisson_solver(const PoissonOptions& options,
                                                    const LinearSolverOptions& linear);
std::unique_ptr<ImplicitSolver> make_ssd_solver(const SsdOptions& options,
                                                const LinearSolverOptions& linear);
std::unique_ptr<ImplicitSolver> make_spectral_solver(const SpectralOptions& options,
                                                     const LinearSolverOptions& linear);

}  // namespace pdd::detail
