// The Delaunay tets of a point set, built by CGAL's concurrent insertion
// (Parallel_tag, a spatial lock grid) and written out in a canonical order:
// the concurrent containers hand out cells in an order that follows the
// threads' timing, and every sum over the tets downstream must not.
#include "domain/concurrent_delaunay.h"

#include "common/cancellation.h"
#include "domain/triangulation.h"

#include <CGAL/Spatial_lock_grid_3.h>
#include <tbb/parallel_for.h>
#include <tbb/scalable_allocator.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

// CGAL's concurrent triangulation takes its cells and vertices from TBB's
// scalable allocator, which keeps the memory it frees to itself: the domain's
// cells and vertices come from malloc instead, so that a rebuild reuses the
// memory the optimizer's round has just freed (E(T), the old triangulation)
// and gives its own back to the next step.
namespace tbb::detail::d1 {
template <class Base>
class scalable_allocator<CGAL::Triangulation_cell_base_with_info_3<int, pdd::detail::Kernel, Base>>
    : public std::allocator<
          CGAL::Triangulation_cell_base_with_info_3<int, pdd::detail::Kernel, Base>> {};
template <class Base>
class scalable_allocator<CGAL::Triangulation_vertex_base_with_info_3<int, pdd::detail::Kernel, Base>>
    : public std::allocator<
          CGAL::Triangulation_vertex_base_with_info_3<int, pdd::detail::Kernel, Base>> {};
}  // namespace tbb::detail::d1

namespace pdd::detail {
namespace {

using ParallelTds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase, CGAL::Parallel_tag>;
using ParallelDelaunay =
    CGAL::Delaunay_triangulation_3<Kernel, ParallelTds, CGAL::Default,
                                   CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking>>;
static_assert(std::is_base_of_v<std::allocator<ParallelTds::Cell>,
                                tbb::scalable_allocator<ParallelTds::Cell>> &&
                  std::is_base_of_v<std::allocator<ParallelTds::Vertex>,
                                    tbb::scalable_allocator<ParallelTds::Vertex>>,
              "the concurrent triangulation allocates with malloc");

// The even permutations of four corners: the rotations that keep a tet's
// orientation.
constexpr int kEven[12][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 0, 3, 2},
                              {1, 2, 0, 3}, {1, 3, 2, 0}, {2, 0, 1, 3}, {2, 1, 3, 0},
                              {2, 3, 0, 1}, {3, 0, 2, 1}, {3, 1, 0, 2}, {3, 2, 1, 0}};

// The even permutation that makes the corners' indices lexicographically
// smallest (the smallest first, then the smallest of the other three).
int canonical_rotation(const std::array<int, 4>& v) {
  int best = 0;
  for (int p = 1; p < 12; ++p) {
    const std::array<int, 4> a{v[kEven[p][0]], v[kEven[p][1]], v[kEven[p][2]], v[kEven[p][3]]};
    const std::array<int, 4> b{v[kEven[best][0]], v[kEven[best][1]], v[kEven[best][2]],
                               v[kEven[best][3]]};
    if (a < b) best = p;
  }
  return best;
}

// Writes the arrays of concurrent_delaunay (its triangulation freed on return).
void build(const std::vector<Vec3>& points, DelaunayArrays& out) {
  const std::size_t n = points.size();
  if (n == 0) return;
  std::vector<std::pair<Point, int>> items(n);
  CGAL::Bbox_3 box;
  for (std::size_t i = 0; i < n; ++i) {
    items[i] = {to_point(points[i]), static_cast<int>(i)};
    box += items[i].first.bbox();
  }
  CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking> locks(box, 50);
  ParallelDelaunay dt(&locks);
  // In slices of the input's order, so that the run's cancellation is polled
  // in between; CGAL sorts each slice spatially.
  constexpr std::size_t kSlice = std::size_t(1) << 20;
  for (std::size_t begin = 0; begin < n; begin += kSlice) {
    poll();
    dt.insert(items.begin() + begin, items.begin() + std::min(n, begin + kSlice));
  }
  std::vector<std::pair<Point, int>>().swap(items);
  out.vertices = dt.number_of_vertices();
  if (out.vertices != n || dt.dimension() < 3) return;

  // The finite cells, each with its corners' canonical rotation.
  std::vector<ParallelDelaunay::Cell_handle> cells;
  cells.reserve(dt.number_of_finite_cells());
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    if (dt.is_infinite(c)) {
      c->info() = -1;
    } else {
      cells.push_back(c);
    }
    poll_every(cells.size());
  }
  const std::size_t T = cells.size();
  std::vector<std::array<int, 4>> corners(T);
  std::vector<std::uint8_t> rotation(T);
  polled_parallel_for(T, [&](std::size_t t) {
    const auto c = cells[t];
    const std::array<int, 4> v{c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(),
                               c->vertex(3)->info()};
    const int p = canonical_rotation(v);
    rotation[t] = static_cast<std::uint8_t>(p);
    corners[t] = {v[kEven[p][0]], v[kEven[p][1]], v[kEven[p][2]], v[kEven[p][3]]};
  });
  // The tets sorted by their corners: bucketed by the first (a counting
  // sort), each bucket sorted on all cores.
  std::vector<std::size_t> start(n + 1, 0);
  for (const auto& k : corners) ++start[k[0] + 1];
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<int> order(T);
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < T; ++t) order[next[corners[t][0]]++] = static_cast<int>(t);
  }
  polled_parallel_for(n, [&](std::size_t v) {
    std::sort(order.begin() + start[v], order.begin() + start[v + 1],
              [&](int a, int b) { return corners[a] < corners[b]; });
  });
  // Each cell's rank is its info; the corners are read off the cells again
  // rather than kept beside the arrays (this is the rebuild's peak of memory).
  // Written out in the cells' own order (their memory in turn; the arrays are
  // what is reached at random).
  polled_parallel_for(T, [&](std::size_t r) { cells[order[r]]->info() = static_cast<int>(r); });
  std::vector<int>().swap(order);
  std::vector<std::array<int, 4>>().swap(corners);
  out.tets.resize(T);
  out.neighbors.resize(T);
  polled_parallel_for(T, [&](std::size_t t) {
    const auto c = cells[t];
    const int r = c->info();
    const int* p = kEven[rotation[t]];
    for (int i = 0; i < 4; ++i) {
      out.tets[r][i] = c->vertex(p[i])->info();
      out.neighbors[r][i] = c->neighbor(p[i])->info();
    }
  });
  // Each vertex's walks start from the first tet that has it, the infinite
  // vertex's from the first hull face.
  out.vertex_cells.assign(n + 1, -1);
  for (std::size_t r = 0; r < T; ++r)
    for (int i = 0; i < 4; ++i) {
      int& first = out.vertex_cells[out.tets[r][i]];
      if (first < 0) first = static_cast<int>(r);
      if (out.vertex_cells[n] == -1 && out.neighbors[r][i] < 0)
        out.vertex_cells[n] = -2 - static_cast<int>(4 * r + i);
    }
}

}  // namespace

DelaunayArrays concurrent_delaunay(const std::vector<Vec3>& points) {
  DelaunayArrays out;
  build(points, out);
  return out;
}

}  // namespace pdd::detail
