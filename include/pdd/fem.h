// Piecewise-linear finite elements on a tetrahedral mesh (§3.5,
// "Discretization Elements"): f(x) = sum_i phi_i(x) f_i with phi_i the hat
// function of vertex i. Every operator takes a TetMesh whose tets are
// positively oriented (the TetMesh contract) and returns Eigen sparse
// matrices (column-major, int indices).
//
// Conventions shared by every function below:
// - The gradient of f is constant in each tet; G stacks it tet by tet:
//   rows 3t, 3t+1, 3t+2 hold d/dx, d/dy, d/dz in tet t.
// - M_T is the 3|T| x 3|T| diagonal matrix that repeats each tet's volume
//   three times (matching the rows of G); M_V the |V| x |V| lumped mass matrix.
// - Sign of the Laplacian: L is positive semi-definite, L = G^T M_T G, i.e.
//   L_ij = -sum_t l cot(theta) / 6 off the diagonal. This is Eq. (12) with the
//   opposite sign: the paper prints the negative semi-definite form but uses L
//   as a positive form in Eqs. (14) and (17) (an energy's Hessian).
// - Assembly runs in parallel (TBB) and is deterministic: every sum is taken
//   in an order fixed by the mesh, never by thread scheduling.
#pragma once

#include <pdd/domain.h>
#include <pdd/types.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <cstddef>
#include <vector>

namespace pdd {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Volume of every tet (positive for a positively oriented tet).
Eigen::VectorXd tet_volumes(const TetMesh& mesh);

// Lumped vertex masses: each tet gives a quarter of its volume to each of its
// vertices. These are the diagonal of M_V.
Eigen::VectorXd vertex_masses(const TetMesh& mesh);

// The gradient matrix G (3|T| x |V|): row 3t + k, column v holds the k-th
// component of the gradient of the barycentric coordinate of v in tet t.
SparseMatrix gradient_matrix(const TetMesh& mesh);

// G^T v for one vector v_t per tet, without forming G: entry i is the sum over
// the tets t around vertex i of grad(phi_i)|_t . v_t. Tets whose v_t is zero
// cost nothing (the SSD right-hand side: only the tets holding samples).
Eigen::VectorXd gradient_transpose_times(const TetMesh& mesh, const std::vector<Vec3>& per_tet);

// The integrated cotangent Laplacian of Eq. (12), positive semi-definite
// (see the sign convention above): for an edge (i, j),
// L_ij = -sum over tets t containing (i, j) of l_kl cot(theta_kl) / 6, where
// (k, l) is the edge of t opposite (i, j), l_kl its length and theta_kl the
// dihedral angle of t at (k, l); L_ii = -sum_{j != i} L_ij. Equals G^T M_T G.
SparseMatrix cotangent_laplacian(const TetMesh& mesh);

// G^T W G for a block-diagonal W with one symmetric 3x3 block per tet
// (weights[t]): the stiffness matrix of the per-tet metric W_t. With
// W_t = volume_t * I this is the Laplacian; the spectral solver uses it for
// the gradient term at the samples (Eq. (17), G^T S^T C S G; SSD adds Eq.
// (15)'s in place, add_sample_terms below).
// weights.size() must equal the number of tets.
SparseMatrix weighted_stiffness(const TetMesh& mesh, const std::vector<Eigen::Matrix3d>& weights);
// The same for W_t = weights[t] * I.
SparseMatrix weighted_stiffness(const TetMesh& mesh, const std::vector<double>& weights);

// The integrated Hessian of Eq. (11) after Stein et al.: H = D~^T M~_T G~
// (9|V| x |V|), where G~ = [G_x; G_y; G_z] stacks the gradient components,
// D~ is the divergence of a per-vertex 3x3 matrix field and M~_T repeats the
// tet volumes. Row (3a + b) * |V| + v, for a, b in {0, 1, 2} (x, y, z),
// holds (H f)_v,ab = integral over the domain of d_b(phi_v) d_a(f).
// For a linear f this vanishes at every interior vertex (the gradients of
// phi_v sum to zero over its closed star); at a vertex on the boundary of the
// mesh it equals d_a(f) times the boundary integral of phi_v n_b, which is
// not zero: the weak form's boundary term is not dropped (Eq. (11) as printed).
SparseMatrix hessian_matrix(const TetMesh& mesh);

// Which entries of a symmetric matrix are stored: all, or the lower triangle
// alone (rows >= column in each column: half the memory; Eigen reads it with
// selfadjointView<Eigen::Lower>()).
enum class Stored { kAll, kLower };

// The samples' terms of Eq. (15) added into A in place, from the tets that
// hold samples (a small share of the domain's):
//   A += gradient_weight G^T S^T S G + value_weight Phi^T Phi,
// S and Phi of `locations` (locate_points on this mesh); returns G^T S^T N,
// N stacking the samples' `normals`. A's pattern must hold every entry the
// sampled tets couple, as hessian_energy's two rings or any one-ring pattern
// do (std::logic_error otherwise); with kLower A holds its lower triangle.
Eigen::VectorXd add_sample_terms(SparseMatrix& A, const TetMesh& mesh,
                                 const std::vector<Location>& locations,
                                 const std::vector<Vec3>& normals, double gradient_weight,
                                 double value_weight, Stored stored = Stored::kAll);

// The integrated squared Hessian of Eq. (15): H^T M~_V^-1 H (|V| x |V|,
// two-ring sparsity), M~_V the vertex masses repeated for the 9 rows of each
// vertex. Equals gram_matrix(hessian_matrix(mesh), 1 / masses repeated 9
// times) but is computed from each vertex's dense 9 x |ring| block of H:
// 0.9 s on one thread for 30k vertices, H's assembly included, against
// 1.5 s for Eigen's product H^T H alone and 2.6 s for gram_matrix.
SparseMatrix hessian_energy(const TetMesh& mesh, Stored stored = Stored::kAll);

// A^T diag(d) A for any sparse A (d.size() == A.rows()), e.g. the
// bi-Laplacian L M_V^-1 L or Phi^T Phi, all entries or its lower triangle.
// Computed column by column in parallel (Gustavson's algorithm) and
// deterministic; on one thread it runs at the speed of Eigen's (serial)
// sparse product for one-ring matrices.
SparseMatrix gram_matrix(const SparseMatrix& A, const Eigen::VectorXd& d,
                         Stored stored = Stored::kAll);

// The Galerkin product P^T A P (P: n x m, A: n x n symmetric, all entries
// stored or its lower triangle alone), column by column in parallel and
// deterministic: the coarse operators of the multigrid solver, all entries
// or the lower triangle (`result`, by default as A is stored). A and the
// result in double or single precision (Out = float: the multigrid's coarse
// levels); the sums in double, but from a lower triangle into single
// precision, where A's entries above the diagonal are read rounded to it.
template <class Out = double, class Scalar = double>
Eigen::SparseMatrix<Out> galerkin_product(const SparseMatrix& P, const Eigen::SparseMatrix<Scalar>& A,
                                          Stored stored, Stored result);
template <class Out = double, class Scalar = double>
Eigen::SparseMatrix<Out> galerkin_product(const SparseMatrix& P, const Eigen::SparseMatrix<Scalar>& A,
                                          Stored stored = Stored::kAll) {
  return galerkin_product<Out, Scalar>(P, A, stored, stored);
}

// A B, column by column in parallel and deterministic.
SparseMatrix sparse_product(const SparseMatrix& A, const SparseMatrix& B);

// The order in which locate_points visits the points (CGAL's spatial sort:
// each near the one before it). A caller that locates the same points in
// several domains computes it once and passes it on.
std::vector<std::size_t> location_order(const std::vector<Vec3>& points);

// Locates every point in the domain (Domain::locate), in `order` (a
// location_order of these points; computed here when null). Throws
// InputError naming how many points fall outside the domain (and the first).
std::vector<Location> locate_points(const Domain& domain, const std::vector<Vec3>& points,
                                    const std::vector<std::size_t>* order = nullptr);

// The barycentric sampling matrix Phi (|X| x |V|): row p holds the
// barycentric coordinates of point p at the vertices of its tet, so that
// (Phi f)_p = f(p). `locations` come from locate_points on the same mesh
// (domain.mesh()); a location outside the mesh (tet == -1) is an
// std::invalid_argument.
SparseMatrix sampling_matrix(const TetMesh& mesh, const std::vector<Location>& locations);

// The selection matrix S (3|X| x 3|T|) of Eq. (15): rows 3p..3p+2 hold the
// 3x3 identity at columns 3t..3t+2 where t is the tet containing point p,
// so that (S G f) stacks the gradient of f at every point.
SparseMatrix selection_matrix(std::size_t num_tets, const std::vector<Location>& locations);

}  // namespace pdd
