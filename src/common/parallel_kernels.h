// Private to src/: deterministic parallel kernels on Eigen vectors and sparse
// matrices stored by columns. Work is split in blocks fixed by the length
// alone and partial sums are added in block order, so results do not depend
// on the number of threads. Eigen's own products are serial or, with OpenMP,
// sum in an order that follows the thread count.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace pdd::detail {

constexpr Eigen::Index kKernelBlock = 4096;  // entries per task and per partial sum

// body(begin, end) over [0, n) in blocks, in parallel.
template <class Body>
void for_blocks(Eigen::Index n, Body body) {
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, kKernelBlock),
                    [&](const tbb::blocked_range<Eigen::Index>& r) { body(r.begin(), r.end()); });
}

// The sum of term(i) over [0, n): partial sums over fixed blocks, added in order.
template <class Term>
double deterministic_sum(Eigen::Index n, Term term) {
  const Eigen::Index blocks = (n + kKernelBlock - 1) / kKernelBlock;
  std::vector<double> partial(static_cast<std::size_t>(blocks), 0.0);
  tbb::parallel_for(Eigen::Index(0), blocks, [&](Eigen::Index k) {
    double s = 0;
    const Eigen::Index end = std::min(n, (k + 1) * kKernelBlock);
    for (Eigen::Index i = k * kKernelBlock; i < end; ++i) s += term(i);
    partial[static_cast<std::size_t>(k)] = s;
  });
  double s = 0;
  for (double p : partial) s += p;
  return s;
}

inline double deterministic_dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  return deterministic_sum(x.size(), [&](Eigen::Index i) { return x[i] * y[i]; });
}

// y = M^T x: y_j = column j of M . x, summed in double whatever M's scalar.
template <class Scalar>
void transposed_product(const Eigen::SparseMatrix<Scalar>& M, const Eigen::VectorXd& x,
                        Eigen::VectorXd& y) {
  y.resize(M.cols());
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const Scalar* value = M.valuePtr();
  // Four partial sums per column: one sum is a chain of dependent additions
  // that stalls on their latency (the two-ring SSD matrix has 75 per column).
  for_blocks(M.cols(), [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index j = begin; j < end; ++j) {
      double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
      int p = outer[j];
      const int last = outer[j + 1];
      for (; p + 4 <= last; p += 4) {
        s0 += double(value[p]) * x[inner[p]];
        s1 += double(value[p + 1]) * x[inner[p + 1]];
        s2 += double(value[p + 2]) * x[inner[p + 2]];
        s3 += double(value[p + 3]) * x[inner[p + 3]];
      }
      for (; p < last; ++p) s0 += double(value[p]) * x[inner[p]];
      y[j] = (s0 + s1) + (s2 + s3);
    }
  });
}

// y = A x for a symmetric A with every entry stored (A = A^T).
template <class Scalar>
void symmetric_product(const Eigen::SparseMatrix<Scalar>& A, const Eigen::VectorXd& x,
                       Eigen::VectorXd& y) {
  transposed_product(A, x, y);
}

// y = A x for a symmetric A given whole (every entry stored) or by its lower
// triangle alone (rows >= column in each column: half the memory). Lower:
// column j gathers y_j and scatters to the rows below it. The columns are
// cut into a fixed number of parts of equal non-zeros, each scattering past
// its own columns into a buffer of its own; the buffers are added in part
// order, so the result does not depend on the number of threads.
template <class Scalar>
class SymmetricProduct {
 public:
  SymmetricProduct() = default;
  SymmetricProduct(const Eigen::SparseMatrix<Scalar>& A, bool lower) : A_(&A), lower_(lower) {
    if (!lower) return;
    const Eigen::Index n = A.cols();
    const int* outer = A.outerIndexPtr();
    const Eigen::Index parts = std::clamp<Eigen::Index>(n / kMinPart, 1, kParts);
    end_.push_back(0);
    for (Eigen::Index p = 1; p < parts; ++p) {
      const long long target = static_cast<long long>(outer[n]) * p / parts;
      end_.push_back(static_cast<Eigen::Index>(
          std::lower_bound(outer + end_.back(), outer + n, target) - outer));
    }
    end_.push_back(n);
    std::size_t total = 0;
    for (std::size_t p = 0; p + 1 < end_.size(); ++p) {
      offset_.push_back(total);
      total += static_cast<std::size_t>(n - end_[p + 1]);
    }
    buffer_.resize(total);
  }

  const Eigen::SparseMatrix<Scalar>& matrix() const { return *A_; }
  bool lower() const { return lower_; }
  // The entries of A (both triangles counted).
  Eigen::Index nonzeros() const {
    return lower_ ? 2 * A_->nonZeros() - A_->rows() : A_->nonZeros();
  }

  // Not reentrant: the buffers are shared by the calls.
  void operator()(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    if (!lower_) return transposed_product(*A_, x, y);
    const Eigen::Index n = A_->cols();
    y.resize(n);
    const int* outer = A_->outerIndexPtr();
    const int* inner = A_->innerIndexPtr();
    const Scalar* value = A_->valuePtr();
    const std::size_t parts = end_.size() - 1;
    tbb::parallel_for(std::size_t(0), parts, [&](std::size_t part) {
      const Eigen::Index begin = end_[part], end = end_[part + 1];
      double* out = buffer_.data() + offset_[part];  // row i >= end at out[i - end]
      std::fill(out, out + (n - end), 0.0);
      std::fill(y.data() + begin, y.data() + end, 0.0);
      for (Eigen::Index j = begin; j < end; ++j) {
        const double xj = x[j];
        double s0 = 0, s1 = 0;
        int p = outer[j];
        const int last = outer[j + 1];
        for (; p + 2 <= last; p += 2) {
          const int i0 = inner[p], i1 = inner[p + 1];
          const double v0 = double(value[p]), v1 = double(value[p + 1]);
          s0 += v0 * x[i0];
          s1 += v1 * x[i1];
          if (i0 != j) (i0 < end ? y[i0] : out[i0 - end]) += v0 * xj;
          (i1 < end ? y[i1] : out[i1 - end]) += v1 * xj;  // i1 > i0 >= j
        }
        if (p < last) {
          const int i = inner[p];
          s0 += double(value[p]) * x[i];
          if (i != j) (i < end ? y[i] : out[i - end]) += double(value[p]) * xj;
        }
        y[j] += s0 + s1;
      }
    });
    for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
      for (std::size_t part = 0; part < parts && end_[part + 1] < end; ++part) {
        const double* in = buffer_.data() + offset_[part];
        const Eigen::Index first = end_[part + 1];
        for (Eigen::Index i = std::max(begin, first); i < end; ++i) y[i] += in[i - first];
      }
    });
  }

 private:
  static constexpr Eigen::Index kParts = 8;      // the most parts (and threads) a product uses
  static constexpr Eigen::Index kMinPart = 512;  // columns
  const Eigen::SparseMatrix<Scalar>* A_ = nullptr;
  bool lower_ = false;
  std::vector<Eigen::Index> end_;      // the parts' columns: [end_[p], end_[p + 1])
  std::vector<std::size_t> offset_;    // part p's rows [end_[p + 1], n) in buffer_
  mutable std::vector<double> buffer_;
};

}  // namespace pdd::detail

namespace pdd::detail {

// X += w Y in place, column by column in parallel, when every entry of Y has
// a place in X (compressed, rows sorted); returns false, X unchanged, when
// one has not. A sum of operators whose patterns nest (one-ring terms into a
// two-ring one) then needs no new allocation. With `lower`, X holds a lower
// triangle (SymmetricProduct) and only Y's entries on or below the diagonal
// are added.
inline bool add_into(Eigen::SparseMatrix<double>& X, const Eigen::SparseMatrix<double>& Y,
                     double w, bool lower = false) {
  if (X.rows() != Y.rows() || X.cols() != Y.cols() || !X.isCompressed() || !Y.isCompressed())
    return false;
  const int* xo = X.outerIndexPtr();
  const int* xi = X.innerIndexPtr();
  double* xv = X.valuePtr();
  const int* yo = Y.outerIndexPtr();
  const int* yi = Y.innerIndexPtr();
  const double* yv = Y.valuePtr();
  const Eigen::Index n = X.cols();
  // First check, so that X is left as it was when a place is missing.
  const double missing = deterministic_sum(n, [&](Eigen::Index j) {
    int p = xo[j];
    for (int q = yo[j]; q < yo[j + 1]; ++q) {
      if (lower && yi[q] < j) continue;
      while (p < xo[j + 1] && xi[p] < yi[q]) ++p;
      if (p == xo[j + 1] || xi[p] != yi[q]) return 1.0;
    }
    return 0.0;
  });
  if (missing > 0) return false;
  for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index j = begin; j < end; ++j) {
      int p = xo[j];
      for (int q = yo[j]; q < yo[j + 1]; ++q) {
        if (lower && yi[q] < static_cast<int>(j)) continue;
        while (xi[p] < yi[q]) ++p;
        xv[p] += w * yv[q];
      }
    }
  });
  return true;
}

// X += w Y: in place when add_into can, as a new sum otherwise.
inline void add_to(Eigen::SparseMatrix<double>& X, const Eigen::SparseMatrix<double>& Y, double w,
                   bool lower = false) {
  if (add_into(X, Y, w, lower)) return;
  if (lower)
    X += w * Eigen::SparseMatrix<double>(Y.triangularView<Eigen::Lower>());
  else
    X += w * Y;
}

}  // namespace pdd::detail
