// Private to src/solvers: the coarse levels of the multigrid, taken from the
// progressive loop itself. A refined domain keeps the indices of the domain
// it was refined from and appends the new vertices (domain.h), so the
// domains of the earlier iterations are prefixes of the current vertex
// array. A coarse level is the largest earlier domain that fits in its size,
// whole, and an even share of all the vertices added since (drawn by a hash
// of their index), so that the regions the last refinements filled coarsen
// too; a level is the Delaunay triangulation of its vertices at their
// current positions, and its prolongation interpolates it barycentrically.
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
  // Each coarse level has 1 / ratio of the vertices of the next finer one,
  // and holds the largest earlier domain that fits and an even share of the
  // later vertices of the finer level. No level has fewer than `coarsest`
  // vertices but the last.
  ProgressiveHierarchy(double ratio, std::size_t coarsest);

  // The prolongations for a system on `vertices` (finest first: the first
  // maps level 1 to the system's level 0), then remembers this domain's size
  // for the next call. Unknown u is domain vertex original[u] (empty: u), at
  // vertices[u]; each coarse level's unknowns keep the system's order.
  const std::vector<SparseMatrix>& levels_for(const std::vector<Vec3>& vertices,
                                              const std::vector<int>& original = {});

  // Remembers a domain of n vertices for the next call, when it is solved
  // without the hierarchy (directly).
  void remember(std::size_t n);

 private:
  double ratio_;
  std::size_t coarsest_;
  std::vector<std::size_t> history_;         // the earlier domains' sizes, increasing
  std::vector<SparseMatrix> prolongations_;  // the last levels_for's, finest first
};

}  // namespace pdd::detail
