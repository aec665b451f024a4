// The domain optimizer of §3.3: one round moves the domain's vertices to the
// minimizer of the quadratic energy E(T) of Eq. (1) (ASAP + mid-edge +
// damping), rebuilds the Delaunay triangulation and carries f over.
#pragma once

#include <pdd/domain.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace pdd {

struct OptimizerOptions {
  double lambda_asap = 60;       // λa, Eq. (1). The paper uses 3; on the shared data 60 gives
                                 // better-shaped isotriangles and smaller distances (with 3
                                 // the mid-edge term, weighted by area rather than volume,
                                 // outweighs ASAP 2r/h to 1 near the surface); see
                                 // docs/benchmarks.md, "Optimizer weights".
  double lambda_mid_edge = 3;    // λm, Eq. (1)
  double damping_weight = 100;   // w_d in units where r(T) = 1 (the paper's 100 / r(T)), Eq. (10)
  bool asap = true;              // ASAP term, Eqs. (2)-(7)
  bool mid_edge = true;          // mid-edge term, Eq. (8)
  bool damping = true;           // damping term away from the boundary, Eqs. (9)-(10)
  double boundary_band = 0.02;   // vertices closer than this * r(T) to ∂T (and all hull and
                                 // sphere vertices) are held fixed: g_d = 1 as a hard constraint
  double cg_tolerance = 1e-6;    // CG stops at this relative residual
  int cg_max_iterations = 2000;  // ... or after this many iterations
  double min_distance_ratio = 0.1;  // guard: a vertex may not come closer to another one than
                                    // this fraction of its shortest edge before the round
};

struct OptimizerReport {
  double energy_before = 0;  // E(T) at the old positions (dimensionless: lengths in units of r(T))
  double energy_after = 0;   // the same function (same constants) at the accepted positions
  int cg_iterations = 0;     // iterations of the conjugate gradient
  double cg_residual = 0;    // its final relative residual
  int rejected_moves = 0;    // vertices sent back to their old position by the guard
  double step_scale = 1;     // factor applied to the remaining moves so that E does not rise
  int crossing_tets = 0;     // |T_S|, tets crossed by f = 0
  int fixed_vertices = 0;    // vertices held by the boundary constraint
  double max_displacement = 0;  // largest vertex move / r(T)
  double diameter = 0;       // r(T), the diameter of the triangulation
};

// E(T) of Eq. (1) for a round: the constants (S* per tet, p_e and n_{a_t},
// g_d, the weights) are frozen at the current domain, which leaves a
// quadratic in the 3|V| stacked coordinates x (x[3 i + k] = coordinate k of
// vertex i):  E(x) = x^T A x - 2 b^T x + c.
struct DomainEnergy {
  Eigen::SparseMatrix<double> A;  // 3|V| x 3|V|, symmetric positive semi-definite
  Eigen::VectorXd b;
  double c = 0;
  std::vector<bool> fixed;        // per vertex: held by the boundary constraint
  double diameter = 0;            // r(T)
  int crossing_tets = 0;          // |T_S|

  double value(const Eigen::VectorXd& x) const;
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;  // 2 (A x - b)
};

// The vertex positions stacked as x[3 i + k].
Eigen::VectorXd stacked_positions(const Domain& domain);

// r(T): the largest distance between two vertices (attained on the hull).
double triangulation_diameter(const Domain& domain);

// Builds E(T) for the current domain. The isosurface is the zero set of
// domain.f() (a value of 0 counts as positive).
DomainEnergy domain_energy(const Domain& domain, const OptimizerOptions& options = {});

// One optimization round (§3.3): minimizes E(T) by CG started from the current
// positions, guards the move (no vertex leaves the domain or comes onto
// another, see min_distance_ratio; no tet of the new triangulation is flat;
// E never rises), then Domain::move_vertices. Hull vertices never move.
OptimizerReport optimize_domain(Domain& domain, const OptimizerOptions& options = {});

}  // namespace pdd
