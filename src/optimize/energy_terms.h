// Private to src/optimize: the three terms of E(T), Eq. (1), each adding its
// quadratic pieces to a common accumulator, and the boundary of the domain.
#pragma once

#include <pdd/domain.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace pdd::optimize_detail {

using Triplet = Eigen::Triplet<double>;

// E(x) = x^T A x - 2 b^T x + c over x[3 i + k], accumulated term by term.
// `isotropic` entries (i, j, a) stand for a * I_3 on the 3x3 block of vertices
// (i, j) (terms that treat the three coordinates alike); `coupled` entries
// index the 3|V| unknowns directly.
struct QuadraticAccumulator {
  std::vector<Triplet> isotropic;
  std::vector<Triplet> coupled;
  Eigen::VectorXd b;
  double c = 0;
};

// ASAP term, Eqs. (2)-(7), every tet weighted by weight_scale * vol(t).
void add_asap_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q);

// Mid-edge term, Eq. (8), every crossed tet weighted by weight_scale * area(a_t).
void add_mid_edge_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q);

// g_d(v) of Eq. (9) for every vertex (0 for all when no tet is crossed).
std::vector<double> damping_factors(const Domain& domain);

// Damping term, Eq. (10): weight * g_d(v) * |v - v~|^2 for every vertex not fixed.
void add_damping_term(const Domain& domain, const std::vector<bool>& fixed, double weight,
                      QuadraticAccumulator& q);

// The triangular faces of the hull ∂T (faces of tets without a neighbor).
std::vector<std::array<int, 3>> hull_faces(const Domain& domain);

// Vertices held by the boundary constraint: hull vertices, vertices flagged on
// the boundary sphere, and vertices closer than `band` to ∂T.
std::vector<bool> boundary_vertices(const Domain& domain, double band);

}  // namespace pdd::optimize_detail
