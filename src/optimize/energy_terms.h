// Private to src/optimize: the three terms of E(T), Eq. (1), each adding its
// quadratic pieces to a common accumulator, and the boundary of the domain.
#pragma once

#include <pdd/domain.h>
#include <pdd/optimize.h>

#include "common/cancellation.h"
#include "common/vertex_stars.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace pdd::optimize_detail {

// E(x) = x^T A x - 2 b^T x + c over x[3 i + k], accumulated term by term
// into the 3x3 blocks of A, one per pair of vertices joined by an edge of the
// domain and one per vertex (every term couples vertices of a common tet).
// A block is a I_3 (terms that treat the three coordinates alike) plus, on
// the blocks the mid-edge term reaches, a full 3x3 part. Summing into the
// blocks of a known pattern, in a fixed order, needs no triplet list (16
// entries per tet and 144 per crossing tet) and no sort.
class QuadraticAccumulator {
 public:
  explicit QuadraticAccumulator(const Domain& domain);

  void add_isotropic(int i, int j, double a) { isotropic_[block(i, j)] += a; }
  void add_coupled(int i, int j, const Eigen::Matrix3d& m);

  // For every vertex j, in parallel: column(j, add) calls add(i, a) to add
  // a I_3 to block (i, j), and may add to b's entries of j. One task sums
  // each column, in the order `column` gives, so the result does not depend
  // on the scheduling.
  template <class Column>
  void add_isotropic_by_columns(Column column) {
    const int n = static_cast<int>(offsets_.size()) - 1;
    // Per thread, the block of each row vertex in the current column: a
    // table lookup instead of a search of the column for every term.
    detail::PerThreadTable slots = detail::per_thread_table(n);
    detail::polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
      std::vector<int>& slot = slots.local();
      for (int j = r.begin(); j < r.end(); ++j) {
        for (int s = offsets_[j]; s < offsets_[j + 1]; ++s) slot[rows_[s]] = s;
        column(j, [&](int i, double a) {
          const int s = slot[i];
          if (s < offsets_[j] || s >= offsets_[j + 1]) no_block();
          isotropic_[s] += a;
        });
      }
    });
  }

  // The same for full 3x3 blocks: column(j, add, adding) calls add(i, m) to
  // add m to block (i, j). It is called twice per column, first to find the
  // blocks (adding false: add only records), then to add (adding true: the
  // time to add to b's entries of j too).
  template <class Column>
  void add_coupled_by_columns(Column column) {
    const int n = static_cast<int>(offsets_.size()) - 1;
    detail::PerThreadTable slots = detail::per_thread_table(n);
    std::vector<char> touched(rows_.size(), 0);
    auto each_column = [&](auto&& visit, bool adding) {
      detail::polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
        std::vector<int>& slot = slots.local();
        for (int j = r.begin(); j < r.end(); ++j) {
          for (int s = offsets_[j]; s < offsets_[j + 1]; ++s) slot[rows_[s]] = s;
          column(j, [&](int i, const Eigen::Matrix3d& m) {
            const int s = slot[i];
            if (s < offsets_[j] || s >= offsets_[j + 1]) no_block();
            visit(s, m);
          }, adding);
        }
      });
    };
    each_column([&](int s, const Eigen::Matrix3d&) { touched[s] = 1; }, false);
    std::size_t added = 0;
    for (std::size_t s = 0; s < touched.size(); ++s) added += touched[s] && coupled_index_[s] < 0;
    coupled_.reserve(coupled_.size() + added);  // grown by doubling, it held up to twice that
    for (std::size_t s = 0; s < touched.size(); ++s) {
      if (touched[s] && coupled_index_[s] < 0) {
        coupled_index_[s] = static_cast<int>(coupled_.size());
        coupled_.push_back(Eigen::Matrix3d::Zero());
      }
      detail::poll_every(s);  // the run's cancellation
    }
    each_column([&](int s, const Eigen::Matrix3d& m) { coupled_[coupled_index_[s]] += m; }, true);
  }

  // The tets around each vertex, in increasing order.
  const detail::VertexStars& stars() const { return stars_; }

  // A, with the entries that the terms left zero off the block diagonals
  // of the isotropic blocks not stored.
  Eigen::SparseMatrix<double> matrix() const;

  // y = A x from the blocks, all of a vertex's three rows at once: a third
  // of matrix()'s memory (12 bytes per isotropic block against 36) and of
  // its reads per product.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  // Vertex v's 3x3 block on A's diagonal.
  Eigen::Matrix3d diagonal_block(int v) const;

  // Frees what only the terms need (the stars), once they are all added.
  void finish_terms() { stars_ = detail::VertexStars(); }

  Eigen::VectorXd b;
  double c = 0;

 private:
  int block(int i, int j) const;  // index of block (i, j) in column j's blocks
  [[noreturn]] static void no_block();  // a term coupled two vertices of no common tet

  detail::VertexStars stars_;
  std::vector<int> offsets_;  // |V| + 1: column j's blocks are offsets_[j] ... offsets_[j + 1) - 1
  std::vector<int> rows_;     // the row vertex of each block, sorted within a column
  std::vector<double> isotropic_;
  std::vector<int> coupled_index_;  // per block: its full part in coupled_, or -1
  std::vector<Eigen::Matrix3d> coupled_;
};

// E(T) as optimize_domain uses it: A kept in the accumulator's blocks
// (domain_energy converts it to a sparse matrix).
struct BlockEnergy {
  explicit BlockEnergy(const Domain& domain) : quadratic(domain) {}
  QuadraticAccumulator quadratic;  // A, b and c
  std::vector<bool> fixed;         // per vertex: held by the boundary constraint
  double diameter = 0;             // r(T)
  int crossing_tets = 0;           // |T_S|
};
BlockEnergy block_energy(const Domain& domain, const OptimizerOptions& options);

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
