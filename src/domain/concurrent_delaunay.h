// Private to src/: the Delaunay tets of a point set built on all cores, as the
// domain's dense arrays in an order that does not depend on the threads.
#pragma once

#include <pdd/types.h>

#include "domain/triangulation.h"

#include <array>
#include <cstddef>
#include <vector>

namespace pdd::detail {

struct DelaunayArrays {
  std::size_t vertices = 0;                   // distinct points (fewer: two coincide)
  std::vector<std::array<int, 4>> tets;       // corners, positively oriented
  std::vector<std::array<int, 4>> neighbors;  // across the face opposite corner i; -1: the hull
  // Where point location starts its walks from each vertex, the infinite one
  // last: a tet containing it, or -2 - (4 t + i) for the hull face i of tet t
  // (Domain::Impl::release's encoding).
  std::vector<int> vertex_cells;
};

// The Delaunay triangulation of `points` (CGAL's, with its symbolic
// perturbation: unique whatever the insertion order), built by CGAL's
// concurrent insertion, then each tet's corners rotated so that the smallest
// index comes first and the tets sorted. Empty tets when the points span fewer
// than three dimensions or when two coincide (`vertices` counts the distinct).
DelaunayArrays concurrent_delaunay(const std::vector<Vec3>& points);

// The inverse, with no predicate: `dt` (cleared) gets a cell per tet, in
// order, with the tet's index as info and the corners in the same order, and
// the infinite cells across the hull faces; vertex i has info i. `handles`
// and `cells` map the indices to the handles.
void triangulation_from_arrays(const TetMesh& mesh,
                               const std::vector<std::array<int, 4>>& neighbors,
                               const std::vector<int>& vertex_cells, Delaunay& dt,
                               std::vector<Delaunay::Vertex_handle>& handles,
                               std::vector<Delaunay::Cell_handle>& cells);

}  // namespace pdd::detail
