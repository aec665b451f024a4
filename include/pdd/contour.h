// Marching tetrahedra (§2.1, §3.4): the isosurface f = isovalue of a
// piecewise-linear function given at the vertices of a tetrahedral mesh.
#pragma once

#include <pdd/types.h>

#include <array>
#include <vector>

namespace pdd {

struct IsoSurface {
  TriangleMesh mesh;           // outward-facing triangles (f < 0 inside)
  std::vector<int> facet_tet;  // for each face: the index of the tet it came from
  std::vector<std::array<int, 2>>
      vertex_edge;  // for each isovertex: the domain edge (a < b) it lies on
};

// Marching tetrahedra on a piecewise-linear f over the tets (§2.1, §3.4).
//
// - A tet whose vertices change sign yields one triangle (1/3 case) or a
//   quadrangle split along its shortest diagonal into two triangles (2/2
//   case, §3.4); both triangles of a quadrangle carry the same facet_tet.
// - One isovertex per crossing edge, shared by every facet around that edge;
//   isovertices are numbered in order of first appearance when scanning the
//   tets in order, so the output depends only on the input.
// - Symbolic perturbation: a value equal to the isovalue counts as positive
//   (outside). The surface is that of a generic f, hence always edge-manifold
//   and closed wherever it does not reach the boundary of the mesh. On an
//   edge from f(a) < isovalue to f(b) >= isovalue the isovertex is at
//   parameter t = (isovalue - f(a)) / (f(b) - f(a)) in (0, 1]; t = 1 (the
//   isovertex sits exactly on b) when f(b) == isovalue. Several isovertices
//   may then coincide at b and some triangles have zero area: the geometry is
//   degenerate there but the connectivity stays that of a manifold.
// - Each triangle faces from the negative vertices of its tet to the positive
//   ones (outward: towards increasing f). This relies on the TetMesh contract
//   that every tet is positively oriented; it is decided combinatorially, so
//   it holds for degenerate triangles too.
//
// Throws std::invalid_argument if f does not have one finite value per vertex.
IsoSurface marching_tetrahedra(const TetMesh& mesh, const std::vector<double>& f,
                               double isovalue = 0.0);

// What a removal of components took away.
struct RemovedComponents {
  int components = 0;  // components removed
  int faces = 0;       // their triangles
};

// Removes the connected components (through shared vertices) whose
// bounding-box diagonal is under min_edges times the mean edge length of the
// whole mesh: blobs of a few triangles, below the resolution the mesh has,
// that f leaves where it dips under zero between the samples of a sparse or
// noisy input (docs/benchmarks.md, "Small components"). The component with
// the most faces always stays. Not in the paper. The vertices of the removed
// components go with them, the others keep their order; min_edges = 0 keeps
// everything.
// Throws std::invalid_argument if min_edges is negative or not finite.
RemovedComponents remove_small_components(TriangleMesh& mesh, double min_edges);

// Removes the components that have boundary edges (an edge of one face
// only), except the one with the most faces. Marching tetrahedra on a closed
// domain leaves a surface open only where it reaches the domain's boundary,
// so such a component is the solver's far field crossing zero there, away
// from the data (the spectral solver's on the kitten for some seeds,
// docs/benchmarks.md, "Small components"); a main surface that runs into the
// boundary (a one-view scan's invented back) stays. Not in the paper.
RemovedComponents remove_open_components(TriangleMesh& mesh);

// The edges of one face only: 0 for a closed mesh.
std::size_t count_boundary_edges(const TriangleMesh& mesh);

// Removes the components, but the largest, that too few of `samples`
// support (are nearest to): fewer than min_samples, or fewer per unit area
// than a tenth of the whole mesh's samples per unit area. The blobs and
// bubbles that stray points left (outliers the test of outliers.h could not
// tell from the surface, clusters of them inside a solid) make such
// components; a part of the shape is supported by every sample on it.
// min_samples = 0 keeps everything.
// Throws std::invalid_argument if min_samples is negative.
RemovedComponents remove_unsupported_components(TriangleMesh& mesh,
                                                const std::vector<Vec3>& samples,
                                                int min_samples);

// Handles of the output that its samples contradict: a tunnel through a wall
// thinner than the sample spacing, a bridge across a gap narrower than it.
struct HandleOptions {
  bool enabled = true;
  double support_degrees = 45;  // a face is supported by a sample whose normal is this close to its own
  double radius_spacings = 3;   // ... within this many average sample spacings of its centroid
  int band_rings = 2;           // rings of faces around a cluster of unsupported faces cut away
};

struct CutHandles {
  int handles = 0;  // handles cut (the genus falls by as many)
  int faces = 0;    // the triangles of their waists, replaced by two caps each
};

// Finds the clusters of faces that lie near samples none of whose normals
// agrees with theirs (by the options' angle and radius), grows each by
// band_rings rings of faces, and where that band is an annulus whose removal
// leaves the mesh in as many pieces (the waist of a handle, not of a limb),
// removes it and fills the two holes (CGAL, refined and faired). Samples
// without normals: nothing is done. Not in the paper.
// Throws std::invalid_argument if an option is out of range.
CutHandles cut_unsupported_handles(TriangleMesh& mesh, const PointSet& samples,
                                   const HandleOptions& options = {});

// Cuts the closed mesh along every cycle of three edges that bounds no face
// and does not separate it (a handle pinched to one triangle's worth, below
// any resolution; the clean-up's collapses can leave one) and closes both
// sides with a triangle. Returns how many; the genus falls by as many.
int cut_triangle_waists(TriangleMesh& mesh);

struct CleanupOptions {
  double max_dihedral_degrees = 30;  // only where neighbouring triangles turn by at most this
  double max_deviation = 0.15;       // ... or where the surface moves by at most this fraction of
                                     // the edge: a flip's (caps), a needle's longest (collapses
                                     // to the midpoint), the triangle left by a valence-three
                                     // corner's removal (its longest)
  double needle_angle_degrees = 20;  // triangles with a smaller angle and a shortest edge at
                                     // most half the next are needles: that edge is collapsed
  int relax_rounds = 3;  // rounds of vertex moves toward their neighbours' centroid, then
                         // collapses and flips
};

struct CleanupReport {
  int flips = 0;
  int collapses = 0;
  int moves = 0;  // vertices moved toward their neighbours' centroid
};

// Improves the triangles of a closed or open oriented manifold mesh: Lawson
// edge flips (the shared edge of two triangles is swapped when the angles
// opposite it sum to more than pi; where they turn more than the dihedral
// bound, only if the flip barely moves the surface), then collapses of the
// shortest edge of needles to its midpoint or an end (kept only if the link
// condition holds and no other triangle turns by more than the dihedral
// bound or the collapse barely moves the surface; a valence-three corner that
// breaks the link condition is removed instead, on the same terms), then flips
// again; then `relax_rounds` rounds of vertex moves (each inner vertex
// halfway to its neighbours' centroid, on a quadric fitted to them, only where
// that raises its smallest angle), collapses and flips.
// Orientation, manifoldness and the topology are kept; removed vertices are
// dropped and the rest keep their order. Throws std::invalid_argument if the
// mesh is not an oriented manifold or an option is out of range.
CleanupReport cleanup_isosurface(TriangleMesh& mesh, const CleanupOptions& options = {});

// Swaps the shared edge of two adjacent triangles whose normals differ by at
// most max_dihedral_degrees when the two angles opposite it sum to more than
// pi (Lawson's flips towards a Delaunay surface triangulation), until none
// does. Vertices are untouched; faces keep their orientation. Returns the
// number of flips. Throws std::invalid_argument if the mesh is not an
// oriented manifold or the bound is outside [0, 90).
int flip_flat_edges(TriangleMesh& mesh, double max_dihedral_degrees);

// The samples' attributes at `vertices` (the output's): colours and
// floating-point properties by inverse-squared-distance weighting of the
// `neighbors` nearest samples (rounded for integer colour types), other
// integer properties (labels, indices) from the nearest sample. One Attribute
// per attribute of `samples`, in order.
std::vector<Attribute> interpolate_attributes(const PointSet& samples,
                                              const std::vector<Vec3>& vertices,
                                              int neighbors = 8);

// Trimming a closed surface to the part its samples support (scans with an
// unseen side), as an open manifold mesh.
struct TrimOptions {
  // Keep the surface within this many local sample spacings of a sample (the
  // spacing: the mean nearest-neighbour distance of the sample's 8 nearest, at
  // most twice the average); 0: no trim.
  double distance = 0;
  // Unsupported regions less than this many average spacings across are a
  // scan's gaps: they stay closed.
  double holes = 30;
  // Pieces the cut leaves that are less than this many average spacings across
  // and that fewer than 2 samples have as their nearest piece are dropped.
  double islands = 10;
};

struct TrimReport {
  bool trimmed = false;
  double spacing = 0;       // the samples' average spacing (mean nearest-neighbour distance)
  double area_removed = 0;  // fraction of the surface's area cut away
  int holes_kept = 0;       // unsupported regions kept closed
  RemovedComponents islands;
  int boundary_loops = 0;   // of the trimmed mesh
};

// Cuts `mesh` along the iso-line g = options.distance of g = a vertex's
// distance to its nearest sample in that sample's local spacing (the largest
// of its own and its edges' midpoints', smoothed over the mesh; each sample's
// nearest vertex keeps its own distance), through the triangles: crossed edges get a new vertex, vertices near the line take it
// through themselves (snapped) so that no sliver is made, and the parts where
// g is larger are removed, but for the small unsupported regions (`holes`);
// then small pieces (`islands`) go, and the rim is smoothed (ears removed,
// rim vertices relaxed along it). The mesh stays an oriented manifold, with
// boundary. Throws std::invalid_argument for an option that is negative or
// not finite, or fewer than two samples.
TrimReport trim_to_samples(TriangleMesh& mesh, const std::vector<Vec3>& samples,
                           const TrimOptions& options);

// The number of boundary loops (cycles of edges of one face only) of a mesh.
int boundary_loops(const TriangleMesh& mesh);

}  // namespace pdd
