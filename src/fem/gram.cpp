// Products A^T D A column by column (Gustavson's algorithm), in parallel.
// Hand-written because Eigen's sparse product is serial, and because the
// Hessian energy has a block structure a generic product cannot use:
// 1.5 s for Eigen's H^T H on a 30k-vertex domain (one thread), 0.9 s for
// hessian_energy below including the assembly of H.
#include <pdd/fem.h>

#include "common/cancellation.h"
#include "common/hilbert_order.h"
#include "fem/assembly.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace pdd {
namespace {

// Per-thread dense scratch: a marker per row of the result and an accumulator.
struct Scratch {
  std::vector<int> marker;
  std::vector<double> accumulator;
  std::vector<int> touched;

  // Column j's sums from values(j, add), its rows left sorted in `touched`
  // (the marker holds the column: each column is summed once per pass).
  template <class Values>
  void sum_column(int j, Values& values) {
    touched.clear();
    values(j, [&](int i, double x) {
      if (marker[i] != j) {
        marker[i] = j;
        accumulator[i] = 0.0;
        touched.push_back(i);
      }
      accumulator[i] += x;
    });
    std::sort(touched.begin(), touched.end());
  }
};

tbb::enumerable_thread_specific<Scratch> per_thread_scratch(int rows) {
  return tbb::enumerable_thread_specific<Scratch>([rows] {
    Scratch s;
    s.marker.assign(rows, -1);
    s.accumulator.assign(rows, 0.0);
    return s;
  });
}

// Builds a rows x n matrix column by column. pattern(j, visit) calls visit(i)
// for every row i of column j (repeats allowed); values(j, add) calls
// add(i, x) for every contribution x to entry (i, j), in an order that
// depends only on j. Both run in parallel over j; the result is
// deterministic. The values are summed in slices of the columns taken in
// `order` (all of 0..n-1; increasing when null), prepare(first, last) called
// before each slice's columns [first, last): data that only those columns read.
template <class Pattern, class Values, class Prepare>
SparseMatrix accumulate_columns(int rows, int n, Pattern pattern, Values values,
                                const std::vector<int>* order, Prepare prepare) {
  tbb::enumerable_thread_specific<Scratch> scratch = per_thread_scratch(rows);
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

  auto fill = [&](int j) {
    Scratch& s = scratch.local();
    s.sum_column(j, values);
    long long out = start[j];
    for (int i : s.touched) {
      r_inner[out] = i;
      r_value[out] = s.accumulator[i];
      ++out;
    }
  };
  constexpr int kSlice = 1 << 15;  // polled_parallel_for's
  std::vector<int> identity;
  if (!order) {
    identity.resize(n);
    std::iota(identity.begin(), identity.end(), 0);
    order = &identity;
  }
  for (int begin = 0; begin < n; begin += kSlice) {
    const int end = std::min(n, begin + kSlice);
    const int* columns = order->data();
    prepare(columns + begin, columns + end);
    tbb::parallel_for(tbb::blocked_range<int>(begin, end), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k < r.end(); ++k) fill(columns[k]);
    });
    detail::poll();
  }
  return result;
}
template <class Pattern, class Values>
SparseMatrix accumulate_columns(int rows, int n, Pattern pattern, Values values) {
  return accumulate_columns(rows, n, pattern, values, nullptr, [](const int*, const int*) {});
}
template <class Pattern, class Values>
SparseMatrix accumulate_columns(int n, Pattern pattern, Values values) {
  return accumulate_columns(n, n, pattern, values);
}

// The same in one pass, for products whose columns cost more to sum than
// their entries weigh (galerkin_product: each coarse column sums a few
// hundred columns of the fine matrix, and the two passes above sum each
// twice): each column is summed once and kept, in chunks of columns, until
// all are counted, then copied into the result (a transient of the result's
// size). Columns in increasing order; the same result as the two passes, the
// sums in double and stored in Out.
template <class Out, class Values>
Eigen::SparseMatrix<Out> accumulate_columns_once(int rows, int n, Values values) {
  tbb::enumerable_thread_specific<Scratch> scratch = per_thread_scratch(rows);
  constexpr int kChunk = 256;  // columns
  struct Chunk {
    std::vector<int> count, inner;
    std::vector<Out> value;
  };
  const int chunks = (n + kChunk - 1) / kChunk;
  std::vector<Chunk> kept(static_cast<std::size_t>(chunks));
  detail::polled_parallel_for(
      chunks,
      [&](int c) {
        Scratch& s = scratch.local();
        Chunk& k = kept[static_cast<std::size_t>(c)];
        const int first = c * kChunk, last = std::min(n, first + kChunk);
        for (int j = first; j < last; ++j) {
          s.sum_column(j, values);
          k.count.push_back(static_cast<int>(s.touched.size()));
          for (int i : s.touched) {
            k.inner.push_back(i);
            k.value.push_back(static_cast<Out>(s.accumulator[i]));
          }
        }
        k.inner.shrink_to_fit();  // grown by doubling: up to twice the entries
        k.value.shrink_to_fit();
      },
      128);
  std::vector<long long> start(static_cast<std::size_t>(chunks) + 1, 0);
  for (int c = 0; c < chunks; ++c)
    start[c + 1] = start[c] + static_cast<long long>(kept[c].inner.size());
  if (start[chunks] > std::numeric_limits<int>::max())
    throw std::length_error("fem: product has more non-zeros than an int index can hold");
  Eigen::SparseMatrix<Out> result(rows, n);
  result.resizeNonZeros(static_cast<Eigen::Index>(start[chunks]));
  int* outer = result.outerIndexPtr();
  outer[0] = 0;
  tbb::parallel_for(0, chunks, [&](int c) {
    Chunk& k = kept[static_cast<std::size_t>(c)];
    int at = static_cast<int>(start[c]);
    for (std::size_t q = 0; q < k.count.size(); ++q) {
      at += k.count[q];
      outer[c * kChunk + static_cast<int>(q) + 1] = at;
    }
    std::copy(k.inner.begin(), k.inner.end(), result.innerIndexPtr() + start[c]);
    std::copy(k.value.begin(), k.value.end(), result.valuePtr() + start[c]);
    k = Chunk();
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

SparseMatrix gram_matrix(const SparseMatrix& A, const Eigen::VectorXd& d, Stored stored) {
  if (d.size() != A.rows()) throw std::invalid_argument("gram_matrix: d must have A.rows() entries");
  const Columns a(A);
  const Columns t(A, Columns::Transposed{});  // column k of t is row k of A
  // Rows from `first(j)` on: all, or those on and below the diagonal.
  const bool lower = stored == Stored::kLower;
  const auto first = [&](int j) { return lower ? j : 0; };
  // Column j of A^T D A = sum over rows k of A in column j of d_k A_kj (row k of A)^T.
  return accumulate_columns(
      static_cast<int>(A.cols()),
      [&](int j, auto&& visit) {
        for (int p = a.outer[j]; p < a.outer[j + 1]; ++p)
          for (int q = t.outer[a.inner[p]]; q < t.outer[a.inner[p] + 1]; ++q)
            if (t.inner[q] >= first(j)) visit(t.inner[q]);
      },
      [&](int j, auto&& add) {
        for (int p = a.outer[j]; p < a.outer[j + 1]; ++p) {
          const int k = a.inner[p];
          const double w = d[k] * a.value[p];
          for (int q = t.outer[k]; q < t.outer[k + 1]; ++q)
            if (t.inner[q] >= first(j)) add(t.inner[q], w * t.value[q]);
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

template <class Out, class Scalar>
Eigen::SparseMatrix<Out> galerkin_product(const SparseMatrix& P, const Eigen::SparseMatrix<Scalar>& A,
                                          Stored stored, Stored result) {
  if (A.rows() != A.cols() || P.rows() != A.rows())
    throw std::invalid_argument("galerkin_product: P must have as many rows as A");
  if (!A.isCompressed()) {
    Eigen::SparseMatrix<Scalar> compressed = A;
    compressed.makeCompressed();
    return galerkin_product<Out>(P, compressed, stored, result);
  }
  const Columns p(P);
  const int* a_outer = A.outerIndexPtr();
  const int* a_inner = A.innerIndexPtr();
  const Scalar* a_value = A.valuePtr();
  // A lower triangle gives column k of A below the diagonal; the entries
  // above it are row k of the triangle, copied here by rows with their values
  // in Out's precision (8 bytes per entry for a single-precision result), so
  // that the product below reads them in order rather than one cache miss each.
  struct RowEntry {
    int column;
    Out value;
  };
  std::vector<long long> row_start;
  std::vector<RowEntry> row_entries;
  if (stored == Stored::kLower) {
    const int n = static_cast<int>(A.rows());
    row_start.assign(static_cast<std::size_t>(n) + 1, 0);
    for (int k = 0; k < n; ++k)
      for (int q = a_outer[k]; q < a_outer[k + 1]; ++q)
        if (a_inner[q] > k) ++row_start[static_cast<std::size_t>(a_inner[q]) + 1];
    for (int i = 0; i < n; ++i) row_start[i + 1] += row_start[i];
    detail::poll();
    row_entries.resize(static_cast<std::size_t>(row_start[n]));
    std::vector<long long> cursor(row_start.begin(), row_start.end() - 1);
    for (int k = 0; k < n; ++k)  // by columns: each row's entries in increasing column
      for (int q = a_outer[k]; q < a_outer[k + 1]; ++q)
        if (a_inner[q] > k)
          row_entries[static_cast<std::size_t>(cursor[a_inner[q]]++)] = {
              k, static_cast<Out>(a_value[q])};
    detail::poll();
  }
  const Columns r(P, Columns::Transposed{});  // column i of r is row i of P
  // Column j = P^T (A p_j): A p_j summed first, on its few hundred fine rows,
  // then each fine row's sum mapped through its row of P. Mapping every term
  // of A p_j instead costs 2.5x the additions (4 per term).
  struct Fine {
    std::vector<int> marker;  // the coarse column that last reached each fine row
    std::vector<double> sum;
    std::vector<int> touched;
  };
  const int n = static_cast<int>(A.rows());
  tbb::enumerable_thread_specific<Fine> scratch([n] {
    Fine f;
    f.marker.assign(n, -1);
    f.sum.assign(n, 0.0);
    return f;
  });
  // The fine rows of A p_j, in the order first reached, with their sums.
  auto fine_column = [&](int j) -> Fine& {
    Fine& f = scratch.local();
    f.touched.clear();
    auto add = [&](int i, double x) {
      if (f.marker[i] != j) {  // accumulate_columns_once reaches each column once
        f.marker[i] = j;
        f.sum[i] = x;
        f.touched.push_back(i);
      } else {
        f.sum[i] += x;
      }
    };
    for (int pk = p.outer[j]; pk < p.outer[j + 1]; ++pk) {
      const int k = p.inner[pk];
      const double w = p.value[pk];
      if (!row_start.empty())
        for (long long e = row_start[k]; e < row_start[k + 1]; ++e)
          add(row_entries[e].column, w * static_cast<double>(row_entries[e].value));
      for (int ai = a_outer[k]; ai < a_outer[k + 1]; ++ai)
        add(a_inner[ai], w * static_cast<double>(a_value[ai]));
    }
    return f;
  };
  const int m = static_cast<int>(P.cols());
  // The rows from `first(j)` on: all, or those on and below the diagonal.
  const auto first = [&](int j) { return result == Stored::kLower ? j : 0; };
  return accumulate_columns_once<Out>(m, m, [&](int j, auto&& add) {
    const Fine& f = fine_column(j);
    for (int i : f.touched)
      for (int q = r.outer[i]; q < r.outer[i + 1]; ++q)
        if (r.inner[q] >= first(j)) add(r.inner[q], f.sum[i] * r.value[q]);
  });
}
template SparseMatrix galerkin_product<double, double>(const SparseMatrix&, const SparseMatrix&,
                                                       Stored, Stored);
template SparseMatrix galerkin_product<double, float>(const SparseMatrix&,
                                                      const Eigen::SparseMatrix<float>&, Stored, Stored);
template Eigen::SparseMatrix<float> galerkin_product<float, double>(const SparseMatrix&,
                                                                    const SparseMatrix&, Stored, Stored);
template Eigen::SparseMatrix<float> galerkin_product<float, float>(
    const SparseMatrix&, const Eigen::SparseMatrix<float>&, Stored, Stored);

SparseMatrix hessian_energy(const TetMesh& mesh, Stored stored) {
  const bool lower = stored == Stored::kLower;
  // Column j = sum over v in the ring of j of (1 / m_v) H_v^T (H_v)_{:, j},
  // H_v the 9 x |ring(v)| block of the rows of v. Row (v, ab) of H is read off
  // column v: (H_v)_{ab, k} = sum_t vol_t d_b(phi_v) d_a(phi_k) = (H_k)_{ba, v}.
  // The columns of H are assembled slice by slice, only those the slice's
  // columns read, so that H (9 values per ring entry) is never held whole.
  using namespace detail;
  const int n = static_cast<int>(mesh.vertices.size());
  const VertexStars stars = vertex_stars(mesh);
  const OneRings rings = one_rings(mesh, stars);
  poll();  // the run's cancellation
  const Eigen::VectorXd inverse_mass = vertex_masses(mesh).cwiseInverse();
  // The assembled columns of H: column of vertex u at h + h_start[slot_of[u]],
  // 9 values per vertex of ring(u).
  std::vector<int> slot_of(n, -1), needed;
  std::vector<long long> h_start;
  std::vector<double> h;
  PerThreadTable positions = per_thread_table(n);
  // Each tet's gradients computed where used (four times) rather than stored.
  auto column = [&](int t, int jl, double* out) {
    hessian_column(tet_gradients(mesh, t), jl, out);
  };
  auto prepare = [&](const int* first, const int* last) {
    for (int u : needed) slot_of[u] = -1;
    needed.clear();
    for (const int* j = first; j != last; ++j)
      for (int v : rings[*j])
        if (slot_of[v] < 0) {
          slot_of[v] = static_cast<int>(needed.size());
          needed.push_back(v);
        }
    h_start.assign(needed.size() + 1, 0);
    for (std::size_t i = 0; i < needed.size(); ++i)
      h_start[i + 1] = h_start[i] + 9 * static_cast<long long>(rings[needed[i]].size());
    h.resize(static_cast<std::size_t>(h_start.back()));
    tbb::parallel_for(std::size_t(0), needed.size(), [&](std::size_t i) {
      double local[36];
      std::vector<int>& position = positions.local();
      const Ring ring = rings[needed[i]];
      const int m = static_cast<int>(ring.size());
      for (int k = 0; k < m; ++k) position[ring[k]] = k;
      assemble_column<9, true>(mesh, stars, position, needed[i], m, column, local,
                               h.data() + h_start[i]);
    });
  };
  // Columns in Hilbert order: a slice's rings then overlap, and each column of
  // H is assembled about once.
  const std::vector<int> order = hilbert_order(mesh.vertices);
  return accumulate_columns(
      n, n,
      [&](int j, auto&& visit) {
        for (int v : rings[j])
          for (int k : rings[v])
            if (!lower || k >= j) visit(k);
      },
      [&](int j, auto&& add) {
        const double* hj = h.data() + h_start[slot_of[j]];  // (H_v)_{ab, j} at 3a + b
        for (const int v : rings[j]) {
          const double w = inverse_mass[v];
          const Ring ring = rings[v];
          const double* hv = h.data() + h_start[slot_of[v]];
          // A ring is sorted: with `lower`, its rows >= j only.
          const std::size_t first =
              lower ? static_cast<std::size_t>(std::lower_bound(ring.begin(), ring.end(), j) -
                                               ring.begin())
                    : 0;
          for (std::size_t q = first; q < ring.size(); ++q) {
            const double* hk = hv + 9 * q;  // (H_v)_{ab, k} at 3b + a, k = ring[q]
            double x = 0;
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b) x += hj[3 * a + b] * hk[3 * b + a];
            add(ring[q], w * x);
          }
          hj += 9;
        }
      },
      &order, prepare);
}

}  // namespace pdd
