#include "solvers/block_jacobi.h"

#include "common/cancellation.h"
#include "common/parallel_kernels.h"
#include "common/union_find.h"

#include <pdd/errors.h>

#include <Eigen/Cholesky>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pdd::detail {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

template <class Scalar>
BlockJacobi::BlockJacobi(const Eigen::SparseMatrix<Scalar>& A, double coupling, int max_block) {
  if (max_block > kMaxBlock) throw std::invalid_argument("BlockJacobi: blocks of at most 64");
  const int n = static_cast<int>(A.rows());
  const Eigen::VectorXd diagonal = A.diagonal().template cast<double>();
  if (!(diagonal.minCoeff() > 0))
    throw SolverError("multigrid: the system matrix has a non-positive diagonal entry");
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const Scalar* value = A.valuePtr();

  // The strong couplings i > j, found in parallel (counted per column, then
  // listed), joined strongest first while a group has room, so that a chain
  // of them breaks at its weakest links. Ties go by (j, i): the groups do not
  // depend on the thread count.
  struct Coupling {
    float strength;  // |a_ij| / sqrt(a_ii a_jj)
    int j, i;
  };
  auto strength = [&](int j, int p) {
    const int i = inner[p];
    return i > j ? std::abs(static_cast<double>(value[p])) / std::sqrt(diagonal[i] * diagonal[j])
                 : 0.0;
  };
  std::vector<int> strong_start(static_cast<std::size_t>(n) + 1, 0);
  std::vector<Coupling> strong;
  if (coupling < 1 && max_block > 1) {
    polled_parallel_for(n, [&](int j) {
      int count = 0;
      for (int p = outer[j]; p < outer[j + 1]; ++p) count += strength(j, p) > coupling;
      strong_start[static_cast<std::size_t>(j) + 1] = count;
    });
    for (int j = 0; j < n; ++j) strong_start[j + 1] += strong_start[j];
    strong.resize(static_cast<std::size_t>(strong_start[n]));
    polled_parallel_for(n, [&](int j) {
      int at = strong_start[j];
      for (int p = outer[j]; p < outer[j + 1]; ++p)
        if (const double c = strength(j, p); c > coupling)
          strong[static_cast<std::size_t>(at++)] = {static_cast<float>(c), j, inner[p]};
    });
    tbb::parallel_sort(strong.begin(), strong.end(), [](const Coupling& x, const Coupling& y) {
      if (x.strength != y.strength) return x.strength > y.strength;
      return x.j != y.j ? x.j < y.j : x.i < y.i;
    });
  }
  std::vector<int> parent = singletons(static_cast<std::size_t>(n));
  std::vector<int> size(static_cast<std::size_t>(n), 1);
  for (const Coupling& c : strong) {
    const int a = find_root(parent, c.i), b = find_root(parent, c.j);
    if (a != b && size[a] + size[b] <= max_block) {
      parent[a] = b;
      size[b] += size[a];
    }
  }
  strong = {};
  strong_start = {};
  poll();

  // Groups numbered by their smallest unknown, members in increasing order.
  std::vector<int> group_of_root(static_cast<std::size_t>(n), -1), count;
  for (int v = 0; v < n; ++v) {
    const int r = find_root(parent, v);
    if (size[r] < 2) continue;
    if (group_of_root[r] < 0) {
      group_of_root[r] = static_cast<int>(count.size());
      count.push_back(0);
    }
    ++count[group_of_root[r]];
  }
  const std::size_t groups = count.size();
  block_start_.assign(groups + 1, 0);
  for (std::size_t g = 0; g < groups; ++g) block_start_[g + 1] = block_start_[g] + count[g];
  block_unknown_.resize(static_cast<std::size_t>(block_start_.back()));
  matrix_start_.assign(groups + 1, 0);
  for (std::size_t g = 0; g < groups; ++g)
    matrix_start_[g + 1] = matrix_start_[g] + static_cast<std::size_t>(count[g]) * count[g];
  {
    std::vector<int> fill(block_start_.begin(), block_start_.end() - 1);
    for (int v = 0; v < n; ++v) {
      const int r = find_root(parent, v);
      if (size[r] >= 2) block_unknown_[static_cast<std::size_t>(fill[group_of_root[r]]++)] = v;
    }
  }
  inverse_diagonal_ = diagonal.cwiseInverse();
  for (int v : block_unknown_) inverse_diagonal_[v] = 0;

  // Each block's L^-1, L its Cholesky factor (invert() makes it the block's inverse).
  dense_.resize(matrix_start_.back());
  std::vector<char> definite(groups, 1);
  tbb::parallel_for(std::size_t(0), groups, [&](std::size_t g) {
    const int* members = block_unknown_.data() + block_start_[g];
    const int m = block_start_[g + 1] - block_start_[g];
    Eigen::MatrixXd block(m, m);
    for (int c = 0; c < m; ++c) {
      const int j = members[c];
      const int* first = inner + outer[j];
      const int* last = inner + outer[j + 1];
      for (int a = 0; a < m; ++a) {
        const int* at = std::lower_bound(first, last, members[a]);
        block(a, c) = at != last && *at == members[a] ? static_cast<double>(value[at - inner]) : 0.0;
      }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(block);
    if (llt.info() != Eigen::Success) {
      definite[g] = 0;
      return;
    }
    Eigen::Map<RowMajor>(dense_.data() + matrix_start_[g], m, m) =
        llt.matrixL().solve(Eigen::MatrixXd::Identity(m, m));
  });
  const auto bad = std::find(definite.begin(), definite.end(), 0);
  if (bad != definite.end())
    throw SolverError("multigrid: a block of " +
                      std::to_string(block_start_[bad - definite.begin() + 1] -
                                     block_start_[bad - definite.begin()]) +
                      " strongly coupled unknowns is not positive definite");
}

template BlockJacobi::BlockJacobi(const SparseMatrix&, double, int);
template BlockJacobi::BlockJacobi(const Eigen::SparseMatrix<float>&, double, int);

template <BlockJacobi::Dense kind>
void BlockJacobi::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if ((kind == Dense::kInverse) != inverted_)
    throw std::logic_error(inverted_ ? "BlockJacobi: the factors were inverted"
                                     : "BlockJacobi: the blocks are not inverted yet");
  const Eigen::Index n = r.size();
  z.resize(n);
  for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index i = begin; i < end; ++i)
      z[i] = (kind == Dense::kInverse ? inverse_diagonal_[i] : std::sqrt(inverse_diagonal_[i])) *
             r[i];
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_blocks(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      double local[kMaxBlock];
                      for (std::size_t g = range.begin(); g < range.end(); ++g) {
                        const int* members = block_unknown_.data() + block_start_[g];
                        const int m = block_start_[g + 1] - block_start_[g];
                        const double* M = dense_.data() + matrix_start_[g];
                        for (int a = 0; a < m; ++a) local[a] = r[members[a]];
                        for (int a = 0; a < m; ++a) {
                          double s = 0;
                          if (kind == Dense::kFactorTranspose)
                            for (int c = 0; c < m; ++c) s += M[c * m + a] * local[c];
                          else
                            for (int c = 0; c < m; ++c) s += M[a * m + c] * local[c];
                          z[members[a]] = s;
                        }
                      }
                    });
}

void BlockJacobi::apply_inverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  apply<Dense::kInverse>(r, z);
}

void BlockJacobi::apply_inverse_factor(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  apply<Dense::kFactor>(r, z);
}

void BlockJacobi::apply_inverse_factor_transpose(const Eigen::VectorXd& r,
                                                 Eigen::VectorXd& z) const {
  apply<Dense::kFactorTranspose>(r, z);
}

void BlockJacobi::invert() {
  if (inverted_) return;
  tbb::parallel_for(std::size_t(0), num_blocks(), [&](std::size_t g) {
    const int m = block_start_[g + 1] - block_start_[g];
    Eigen::Map<RowMajor> block(dense_.data() + matrix_start_[g], m, m);
    const RowMajor inverse = block.transpose() * block;
    block = inverse;
  });
  inverted_ = true;
}

}  // namespace pdd::detail
