#include "solvers/hierarchy.h"

#include "common/cancellation.h"
#include "domain/concurrent_delaunay.h"
#include "domain/triangulation.h"

#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace pdd::detail {
namespace {

constexpr std::size_t kChunk = 512;  // queries walked one after the other from the last

// Barycentric coordinates of p in finite cell c, negatives (rounding) set to
// 0, then normalized.
std::array<double, 4> barycentric(Delaunay::Cell_handle c, const Vec3& p) {
  Vec3 q[4];
  for (int i = 0; i < 4; ++i) q[i] = to_vec(c->vertex(i)->point());
  auto volume = [](const Vec3& a, const Vec3& b, const Vec3& d, const Vec3& e) {
    return (b - a).dot((d - a).cross(e - a));
  };
  std::array<double, 4> w{volume(p, q[1], q[2], q[3]), volume(q[0], p, q[2], q[3]),
                          volume(q[0], q[1], p, q[3]), volume(q[0], q[1], q[2], p)};
  double sum = 0;
  for (double& x : w) sum += (x = std::max(x, 0.0));
  for (double& x : w) x /= sum;
  return w;
}

}  // namespace

SparseMatrix subset_prolongation(const std::vector<Vec3>& vertices, const std::vector<int>& coarse,
                                 const std::vector<int>& fine) {
  if (coarse.size() < 4 || coarse.size() > fine.size())
    throw std::invalid_argument("subset_prolongation: need 4 <= |coarse| <= |fine|");
  // The coarse vertices' triangulation, built on all cores (vertex c's info
  // is c), for the fine vertices' point location.
  Delaunay dt;
  {
    TetMesh coarse_mesh;
    coarse_mesh.vertices.reserve(coarse.size());
    for (int c : coarse) coarse_mesh.vertices.push_back(vertices[c]);
    DelaunayArrays built = concurrent_delaunay(coarse_mesh.vertices);
    if (built.vertices != coarse.size() || built.tets.empty())
      throw std::invalid_argument("subset_prolongation: the coarse vertices are degenerate");
    coarse_mesh.tets = std::move(built.tets);
    std::vector<Delaunay::Vertex_handle> handles;
    std::vector<Delaunay::Cell_handle> cells;
    triangulation_from_arrays(coarse_mesh, built.neighbors, built.vertex_cells, dt, handles, cells);
  }

  // Row r of P: up to 4 columns and their weights.
  const std::size_t n = fine.size();
  std::vector<std::array<int, 4>> columns(n, {-1, -1, -1, -1});
  std::vector<std::array<double, 4>> weights(n, {0, 0, 0, 0});
  // The fine vertices that are not coarse, in spatial order, located chunk
  // by chunk, each walk starting from the previous one's cell (a few steps
  // instead of a walk across the domain). The chunks do not depend on the
  // thread count.
  using Item = std::pair<Point, int>;
  std::vector<Item> queries;
  queries.reserve(n - coarse.size());
  for (std::size_t r = 0, c = 0; r < n; ++r) {
    if (c < coarse.size() && coarse[c] == fine[r]) {
      columns[r][0] = static_cast<int>(c++);
      weights[r][0] = 1;
    } else {
      if (c < coarse.size() && coarse[c] < fine[r])
        throw std::invalid_argument("subset_prolongation: coarse is not a subset of fine");
      queries.emplace_back(to_point(vertices[fine[r]]), static_cast<int>(r));
    }
  }
  using Traits =
      CGAL::Spatial_sort_traits_adapter_3<Kernel, CGAL::First_of_pair_property_map<Item>>;
  CGAL::spatial_sort<CGAL::Parallel_tag>(queries.begin(), queries.end(), Traits());
  const std::size_t chunks = (queries.size() + kChunk - 1) / kChunk;
  std::vector<char> outside(queries.size(), 0);
  polled_parallel_for(
      chunks,
      [&](std::size_t k) {
        Delaunay::Cell_handle hint;
        for (std::size_t q = k * kChunk; q < std::min(queries.size(), (k + 1) * kChunk); ++q) {
          const auto& [point, r] = queries[q];
          Delaunay::Locate_type lt;
          int li, lj;
          const Delaunay::Cell_handle c = dt.locate(point, lt, li, lj, hint);
          if (lt == Delaunay::OUTSIDE_CONVEX_HULL || dt.is_infinite(c)) {
            outside[q] = 1;
            continue;
          }
          hint = c;
          const std::array<double, 4> w = barycentric(c, to_vec(point));
          for (int i = 0; i < 4; ++i) {
            columns[r][i] = w[i] > 0 ? c->vertex(i)->info() : -1;
            weights[r][i] = w[i];
          }
        }
      },
      std::size_t(64));
  // The few outside the hull, one after the other: CGAL's nearest_vertex
  // walks the vertices' neighbours by marking cells, which concurrent calls
  // would share (the result then followed the threads' timing).
  Delaunay::Cell_handle hint;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    if (!outside[q]) continue;
    const auto& [point, r] = queries[q];
    Delaunay::Locate_type lt;
    int li, lj;
    hint = dt.locate(point, lt, li, lj, hint);
    columns[r][0] = dt.nearest_vertex(point, hint)->info();
    weights[r][0] = 1;
  }

  // Assembled by rows, then stored by columns.
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows(static_cast<Eigen::Index>(n),
                                                    static_cast<Eigen::Index>(coarse.size()));
  std::size_t nonzeros = 0;
  for (const auto& c : columns)
    for (int j : c) nonzeros += j >= 0;
  rows.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
  int* outer = rows.outerIndexPtr();
  int* inner = rows.innerIndexPtr();
  double* value = rows.valuePtr();
  int out = 0;
  for (std::size_t r = 0; r < n; ++r) {
    outer[r] = out;
    std::array<int, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return columns[r][a] < columns[r][b]; });
    for (int i : order)
      if (columns[r][i] >= 0) {
        inner[out] = columns[r][i];
        value[out++] = weights[r][i];
      }
    poll_every(r);
  }
  outer[n] = out;
  return SparseMatrix(rows);
}

ProgressiveHierarchy::ProgressiveHierarchy(double ratio, std::size_t coarsest)
    : ratio_(ratio), coarsest_(std::max<std::size_t>(coarsest, 4)) {
  if (!(ratio > 1)) throw std::invalid_argument("ProgressiveHierarchy: the ratio must be > 1");
}

const std::vector<SparseMatrix>& ProgressiveHierarchy::levels_for(
    const std::vector<Vec3>& vertices, const std::vector<int>& original) {
  if (!original.empty() && original.size() != vertices.size())
    throw std::invalid_argument("ProgressiveHierarchy: one domain index per unknown is required");
  const std::size_t n = vertices.size();
  // Earlier sizes that are not prefixes of this domain are forgotten.
  history_.erase(std::lower_bound(history_.begin(), history_.end(), n), history_.end());

  // Each vertex's key, uniform in [0, 1) by a hash of its index; a vertex
  // drawn for a level has its key divided by the largest key drawn, so that
  // the keys of each level's drawn vertices are uniform again.
  std::vector<double> key(n);
  for (std::size_t v = 0; v < n; ++v) {
    std::uint64_t h = v + 0x9E3779B97F4A7C15ull;  // splitmix64
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    h ^= h >> 31;
    key[v] = static_cast<double>(h >> 11) * 0x1.0p-53;
  }
  std::vector<std::vector<int>> chain(1);
  chain[0].resize(n);
  std::iota(chain[0].begin(), chain[0].end(), 0);
  while (chain.back().size() > coarsest_) {
    const std::vector<int>& finer = chain.back();
    const auto size = static_cast<std::size_t>(
        std::max(4.0, static_cast<double>(finer.size()) / ratio_));
    if (size >= finer.size()) break;
    // The largest earlier domain that fits is kept whole (the finer level
    // holds it whole too); the rest is drawn from all the later vertices.
    std::size_t kept = 0;
    for (std::size_t b : history_)
      if (b <= size) kept = b;
    std::vector<int> drawn(std::lower_bound(finer.begin(), finer.end(), static_cast<int>(kept)),
                           finer.end());
    const std::size_t count = size - kept;
    std::nth_element(drawn.begin(), drawn.begin() + static_cast<std::ptrdiff_t>(count), drawn.end(),
                     [&](int a, int b) { return key[a] < key[b] || (key[a] == key[b] && a < b); });
    drawn.resize(count);
    double largest = 0;
    for (int v : drawn) largest = std::max(largest, key[v]);
    if (largest > 0)
      for (int v : drawn) key[v] /= largest;
    std::vector<int>& level = chain.emplace_back(kept);
    std::iota(level.begin(), level.end(), 0);
    std::sort(drawn.begin(), drawn.end());
    level.insert(level.end(), drawn.begin(), drawn.end());
  }

  // Each level's unknowns in the system's order.
  if (!original.empty()) {
    std::vector<int> unknown(n, -1);
    for (std::size_t u = 0; u < n; ++u) {
      const int v = original[u];
      if (v < 0 || static_cast<std::size_t>(v) >= n || unknown[v] >= 0)
        throw std::invalid_argument("ProgressiveHierarchy: the unknowns' order is no permutation");
      unknown[v] = static_cast<int>(u);
    }
    for (std::vector<int>& level : chain) {
      for (int& v : level) v = unknown[v];
      std::sort(level.begin(), level.end());
    }
  }
  std::vector<SparseMatrix> prolongations(chain.size() - 1);
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
    subset_prolongation(vertices, chain[k + 1], chain[k]).swap(prolongations[k]);
    poll();
  }
  prolongations_ = std::move(prolongations);
  history_.push_back(n);
  return prolongations_;
}

void ProgressiveHierarchy::remember(std::size_t n) {
  history_.erase(std::lower_bound(history_.begin(), history_.end(), n), history_.end());
  history_.push_back(n);
}

}  // namespace pdd::detail
