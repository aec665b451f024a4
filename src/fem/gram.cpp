// Products A^T D A column by column (Gustavson's algorithm), in parallel.
// Hand-written because Eigen's sparse product is serial, and because the
// Hessian energy has a block structure a generic product cannot use:
// 1.5 s for Eigen's H^T H on a 30k-vertex domain (one thread), 0.9 s for
// hessian_energy below including the assembly of H.
#include <pdd/fem.h>

#include "common/cancellation.h"
#include "fem/assembly.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pdd {
namespace {

// Per-thread dense scratch: a marker per row of the result and an accumulator.
struct Scratch {
  std::vector<int> marker;
  std::vector<double> accumulator;
  std::vector<int> touched;
};

// Builds an n x n matrix column by column. pattern(j, visit) calls visit(i)
// for every row i of column j (repeats allowed); values(j, add) calls
// add(i, x) for every contribution x to entry (i, j), in an order that
// depends only on j. Both run in parallel over j; the result is
// deterministic.
template <class Pattern, class Values>
SparseMatrix accumulate_columns(int rows, int n, Pattern pattern, Values values);
template <class Pattern, class Values>
SparseMatrix accumulate_columns(int n, Pattern pattern, Values values) {
  return accumulate_columns(n, n, pattern, values);
}
template <class Pattern, class Values>
SparseMatrix accumulate_columns(int rows, int n, Pattern pattern, Values values) {
  tbb::enumerable_thread_specific<Scratch> scratch([rows] {
    Scratch s;
    s.marker.assign(rows, -1);
    s.accumulator.assign(rows, 0.0);
    return s;
  });
  std::vector<long long> start(n + 1, 0);
  // Sliced, with the run's cancellation polled in between: a product takes seconds at 1M.
  detail::polled_parallel_for(n, [&](int j) {
    Scratch& s = scratch.local();
    long long count = 0;
    pattern(j, [&](int i) {
      if (s.marker[i] != j) {
        s.marker[i] = j;
        ++count;
      }
    });
    start[j + 1] = count;
  });
  for (int j = 0; j < n; ++j) start[j + 1] += start[j];
  detail::poll();
  if (start[n] > std::numeric_limits<int>::max())
    throw std::length_error("fem: product has more non-zeros than an int index can hold");

  SparseMatrix result(rows, n);
  result.resizeNonZeros(static_cast<Eigen::Index>(start[n]));
  for (int j = 0; j <= n; ++j) result.outerIndexPtr()[j] = static_cast<int>(start[j]);
  int* r_inner = result.innerIndexPtr();
  double* r_value = result.valuePtr();
  for (auto& s : scratch) std::fill(s.marker.begin(), s.marker.end(), -1);

  detail::polled_parallel_for(n, [&](int j) {
    Scratch& s = scratch.local();
    s.touched.clear();
    values(j, [&](int i, double x) {
      if (s.marker[i] != j) {
        s.marker[i] = j;
        s.accumulator[i] = 0.0;
        s.touched.push_back(i);
      }
      s.accumulator[i] += x;
    });
    std::sort(s.touched.begin(), s.touched.end());
    long long out = start[j];
    for (int i : s.touched) {
      r_inner[out] = i;
      r_value[out] = s.accumulator[i];
      ++out;
    }
  });
  return result;
}

// The three arrays of a column-major matrix: read in place when it is
// compressed, from a compressed copy otherwise (Eigen 3.4's SparseMatrix has
// no move: taking it by value copied it twice).
struct Columns {
  struct Transposed {};
  SparseMatrix own;
  const int* outer;
  const int* inner;
  const double* value;
  explicit Columns(const SparseMatrix& a) {
    if (a.isCompressed()) {
      point_at(a);
    } else {
      own = a;
      own.makeCompressed();
      point_at(own);
    }
  }
  // The columns of a's transpose, i.e. its rows.
  Columns(const SparseMatrix& a, Transposed) {
    SparseMatrix(a.transpose()).swap(own);
    own.makeCompressed();
    point_at(own);
  }
  Columns(const Columns&) = delete;
  Columns& operator=(const Columns&) = delete;

 private:
  void point_at(const SparseMatrix& m) {
    outer = m.outerIndexPtr();
    inner = m.innerIndexPtr();
    value = m.valuePtr();
  }
};

}  // namespace

SparseMatrix gram_matrix(const SparseMatrix& A, const Eigen::VectorXd& d) {
  if (d.size() != A.rows()) throw std::invalid_argument("gram_matrix: d must have A.rows() entries");
  const Columns a(A);
  const Columns t(A, Columns::Transposed{});  // column k of t is row k of A
  // Column j of A^T D A = sum over rows k of A in column j of d_k A_kj (row k of A)^T.
  return accumulate_columns(
      static_cast<int>(A.cols()),
      [&](int j, auto&& visit) {
        for (int p = a.outer[j]; p < a.outer[j + 1]; ++p)
          for (int q = t.outer[a.inner[p]]; q < t.outer[a.inner[p] + 1]; ++q) visit(t.inner[q]);
      },
      [&](int j, auto&& add) {
        for (int p = a.outer[j]; p < a.outer[j + 1]; ++p) {
          const int k = a.inner[p];
          const double w = d[k] * a.value[p];
          for (int q = t.outer[k]; q < t.outer[k + 1]; ++q) add(t.inner[q], w * t.value[q]);
        }
      });
}

SparseMatrix sparse_product(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.cols() != B.rows()) throw std::invalid_argument("sparse_product: sizes do not match");
  const Columns a(A), b(B);
  auto for_each_term = [&](int j, auto&& term) {
    for (int pk = b.outer[j]; pk < b.outer[j + 1]; ++pk)
      for (int ai = a.outer[b.inner[pk]]; ai < a.outer[b.inner[pk] + 1]; ++ai)
        term(a.inner[ai], b.value[pk] * a.value[ai]);
  };
  return accumulate_columns(
      static_cast<int>(A.rows()), static_cast<int>(B.cols()),
      [&](int j, auto&& visit) { for_each_term(j, [&](int i, double) { visit(i); }); },
      [&](int j, auto&& add) { for_each_term(j, add); });
}

SparseMatrix galerkin_product(const SparseMatrix& P, const SparseMatrix& A) {
  if (A.rows() != A.cols() || P.rows() != A.rows())
    throw std::invalid_argument("galerkin_product: P must have as many rows as A");
  const Columns p(P), a(A);
  const Columns r(P, Columns::Transposed{});  // column i of r is row i of P
  // Column j = sum over k in column j of P of P_kj sum over i of A_ik (row i of P)^T.
  auto for_each_term = [&](int j, auto&& term) {
    for (int pk = p.outer[j]; pk < p.outer[j + 1]; ++pk)
      for (int ai = a.outer[p.inner[pk]]; ai < a.outer[p.inner[pk] + 1]; ++ai) {
        const int i = a.inner[ai];
        const double w = p.value[pk] * a.value[ai];
        for (int q = r.outer[i]; q < r.outer[i + 1]; ++q) term(r.inner[q], w * r.value[q]);
      }
  };
  return accumulate_columns(
      static_cast<int>(P.cols()),
      [&](int j, auto&& visit) { for_each_term(j, [&](int i, double) { visit(i); }); },
      [&](int j, auto&& add) { for_each_term(j, add); });
}

SparseMatrix hessian_energy(const TetMesh& mesh) {
  // Rows 9v + ab: column j holds, for each v in the ring of j, the 9 entries
  // (H_v)_{ab, j} next to each other. Row (v, ab) of H is read off column v:
  // (H_v)_{ab, k} = sum_t vol_t d_b(phi_v) d_a(phi_k) = (H_k)_{ba, v}, so
  // no transpose of H is needed.
  const SparseMatrix H = detail::hessian_matrix_rows(mesh, true);
  detail::poll();  // the run's cancellation
  const Eigen::VectorXd inverse_mass = vertex_masses(mesh).cwiseInverse();
  const int* h_outer = H.outerIndexPtr();
  const int* h_inner = H.innerIndexPtr();
  const double* h_value = H.valuePtr();
  // Column j = sum over v of (1 / m_v) H_v^T (H_v)_{:, j}, H_v the dense
  // 9 x |ring(v)| block of the rows of v.
  return accumulate_columns(
      static_cast<int>(mesh.vertices.size()),
      [&](int j, auto&& visit) {
        for (int p = h_outer[j]; p < h_outer[j + 1]; p += 9) {
          const int v = h_inner[p] / 9;
          for (int q = h_outer[v]; q < h_outer[v + 1]; q += 9) visit(h_inner[q] / 9);
        }
      },
      [&](int j, auto&& add) {
        for (int p = h_outer[j]; p < h_outer[j + 1]; p += 9) {
          const int v = h_inner[p] / 9;
          const double w = inverse_mass[v];
          const double* hj = h_value + p;  // (H_v)_{ab, j} at 3a + b
          for (int q = h_outer[v]; q < h_outer[v + 1]; q += 9) {
            const double* hk = h_value + q;  // (H_v)_{ab, k} at 3b + a, k = h_inner[q] / 9
            double x = 0;
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b) x += hj[3 * a + b] * hk[3 * b + a];
            add(h_inner[q] / 9, w * x);
          }
        }
      });
}

}  // namespace pdd
