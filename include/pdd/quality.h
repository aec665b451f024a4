// Element quality and surface checks (§2.2, Figure 2): angles of triangles,
// dihedral angles and radius-edge ratios of tetrahedra, and the topology of a
// triangle mesh. All angles are in degrees.
#pragma once

#include <pdd/types.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace pdd {

// Counts of values in equal bins: bin i holds [lower + i w, lower + (i+1) w);
// values below `lower` go to the first bin, values past the end to the last.
struct Histogram {
  double lower = 0;                 // start of the first bin
  double bin_width = 0;             // w
  std::vector<std::size_t> counts;  // one per bin

  double upper() const { return lower + bin_width * static_cast<double>(counts.size()); }
};
// The histogram of `values` in `bins` bins from lower to upper (NaNs are not counted).
Histogram histogram(const std::vector<double>& values, double lower, double upper, int bins);

// Throws InputError "<source>: ..." when the faces' vertices span more than
// 1e150, or less than 1e-150 but more than 0 (their bounding-box diagonal):
// the squares and products of lengths in angles, areas and distances would
// overflow or underflow a double, and the measures come out as NaN or
// nonsense. Called by quality_report and require_area (compare.h).
void require_measurable(const TriangleMesh& mesh, const std::string& source);

// ---------------------------------------------------------------- triangles

// The angles of triangle (a, b, c) at a, b and c. A zero-length side gives
// angles of 0 at its ends; a degenerate triangle has angles 0 (and 180).
std::array<double, 3> triangle_angles(const Vec3& a, const Vec3& b, const Vec3& c);

// The smallest angle of each face of the mesh.
std::vector<double> min_angles(const TriangleMesh& mesh);

struct TriangleQuality {
  std::size_t count = 0;          // number of faces
  double min_angle = 0;           // smallest angle over all faces (0 when there are none)
  double mean_min_angle = 0;      // mean over faces of their smallest angle
  double max_angle = 0;           // largest angle over all faces
  Histogram min_angle_histogram;  // per-face smallest angle, 0-60 in bins of 5
  double fraction_below_10 = 0;   // fraction of faces whose smallest angle is < 10
  double fraction_below_20 = 0;   // ... < 20
  double fraction_below_30 = 0;   // ... < 30
};
TriangleQuality triangle_quality(const TriangleMesh& mesh);

// ---------------------------------------------------------------- tetrahedra

// The six dihedral angles of tet (a, b, c, d), at edges ab, ac, ad, bc, bd, cd
// (the regular tet has acos(1/3) = 70.53 everywhere).
std::array<double, 6> dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

struct TetShape {
  double min_dihedral = 0;  // smallest of the six dihedral angles
  double max_dihedral = 0;  // largest
  double radius_edge = 0;   // circumradius / shortest edge (pdd::radius_edge_ratio); inf when flat
};
// The shape measures of each tet of the mesh.
std::vector<TetShape> tet_shapes(const TetMesh& mesh);

struct TetQuality {
  std::size_t count = 0;                      // number of tets
  double min_dihedral = 0;                    // smallest dihedral angle over all tets
  double max_dihedral = 0;                    // largest dihedral angle over all tets
  double mean_min_dihedral = 0;               // mean over tets of their smallest dihedral angle
  Histogram dihedral_histogram;               // all 6 x count dihedral angles, 0-180 in bins of 10
  double min_radius_edge = 0;                 // best radius-edge ratio (sqrt(6)/4 at best)
  double mean_radius_edge = 0;                // mean radius-edge ratio
  double max_radius_edge = 0;                 // worst radius-edge ratio
  double fraction_min_dihedral_below_10 = 0;  // fraction of tets with a dihedral angle < 10
};
TetQuality tet_quality(const TetMesh& mesh);

// ---------------------------------------------------------------- surfaces

// Topology of a triangle mesh. Only vertices referenced by a face count.
struct SurfaceTopology {
  std::size_t vertices = 0;               // V: referenced vertices
  std::size_t edges = 0;                  // E: distinct undirected edges
  std::size_t faces = 0;                  // F
  std::size_t boundary_edges = 0;         // edges with one face
  std::size_t non_manifold_edges = 0;     // edges with three or more faces
  std::size_t inconsistent_edges = 0;     // edges whose two faces run them the same way
  std::size_t degenerate_faces = 0;       // faces that repeat a vertex index
  std::size_t non_manifold_vertices = 0;  // vertices whose faces form more than one fan
  std::size_t components = 0;             // connected components (through shared vertices)
  long euler_characteristic = 0;          // V - E + F
  // Every edge has 1 or 2 faces, consistently oriented, and no face is degenerate.
  bool edge_manifold = false;
  bool manifold = false;  // edge_manifold and no non-manifold vertex
  bool closed = false;    // no boundary edge (and at least one face)
  long genus = -1;        // sum over components, when closed and manifold; -1 otherwise
};
// Throws std::invalid_argument if a face indexes a missing vertex.
SurfaceTopology surface_topology(const TriangleMesh& mesh);

}  // namespace pdd
