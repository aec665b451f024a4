// Private to src/solvers: the coarse levels of the multigrid, taken from the
// progressive loop itself. A refined domain keeps the indices of the domain
// it was refined from and appends the new vertices (domain.h), so the
// domains of the earlier iterations are prefixes of the current vertex
// array. A coarse level is the Delaunay triangulation of such a prefix at the
// vertices' current positions (the earlier domain, moved by the optimizer
// since), or of a prefix plus an even share of the next iteration's
// vertices where the iterations' sizes leave gaps; its prolongation
// interpolates it barycentrically.
#pragma once

#include <pdd/fem.h>
#include <pdd/types.h>

#include <cstddef>
#include <vector>

namespace pdd::detail {

// P (|fine| x |coarse|) for two sets of vertex indices, sorted, coarse a
// subset of fine; rows and columns follow the sets' order. The row of a
// coarse vertex is its unit vector; the row of another vertex holds its
// barycentric coordinates in the tet of the Delaunay triangulation of the
// coarse vertices that contains it (the nearest coarse vertex when it lies
// outside their hull).
SparseMatrix subset_prolongation(const std::vector<Vec3>& vertices, const std::vector<int>& coarse,
                                 const std::vector<int>& fine);

// The levels of a solver that solves on a sequence of domains, each refined
// from the last.
class ProgressiveHierarchy {
 public:
  // Each coarse level has about 1 / ratio of the vertices of the next finer
  // one: an earlier domain when one has within 30 % of that size, else an
  // earlier domain and the share of the next one's new vertices that makes
  // up the size (picked by a hash of their index, so that they spread over
  // where that iteration refined). No level has fewer than `coarsest`
  // vertices but the last.
  ProgressiveHierarchy(double ratio, std::size_t coarsest);

  // The prolongations for a system on `vertices` (finest first: the first
  // maps level 1 to the system's level 0), then remembers this domain's size
  // for the next calls. The prolongations between coarse levels are kept
  // from the last call where they are the same.
  const std::vector<SparseMatrix>& levels_for(const std::vector<Vec3>& vertices);

  // Remembers a domain of n vertices as a level for the next calls, when it
  // is solved without the hierarchy (directly).
  void remember(std::size_t n);

  // The size of every level of the last levels_for, finest first.
  std::vector<std::size_t> sizes() const;

 private:
  std::vector<int> level(std::size_t n, double target) const;

  double ratio_;
  std::size_t coarsest_;
  std::vector<std::size_t> history_;         // sizes of the earlier domains, increasing
  std::vector<std::vector<int>> chain_;      // the last levels_for's vertex sets, finest first
  std::vector<SparseMatrix> prolongations_;  // the last levels_for's, finest first
};

}  // namespace pdd::detail
