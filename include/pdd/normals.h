// Normals for point sets that come without them, or with an orientation that
// cannot be trusted (photogrammetry, merged scans): estimation by jet fitting
// (CGAL's Point_set_processing_3), sharpened at the features; orientation by
// segments turned by visibility votes, or along a minimum spanning tree
// (CGAL's). The pipeline (pipeline.h) can also orient them along the gradient
// of a coarse solve that needs no orientation.
#pragma once

#include <pdd/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pdd {

// The fewest points from which normals are estimated: a quadratic jet needs six
// neighbours, and the neighbourhoods must not all be the whole set.
constexpr std::size_t kMinPointsForNormals = 16;

// One quadratic jet (osculating quadric, CGAL::Monge_via_jet_fitting) fitted
// to each point and its k nearest neighbours: the point projected
// onto it (noise removed at that scale) and its unit normal, of unknown sign.
// k adapts the neighbourhood's radius to the local density. Each fit also
// gives its neighbourhood's best-fitting plane (PCA), for sharpen_normals.
// Throws InputError naming `source` when there are fewer than
// kMinPointsForNormals points or a neighbourhood is too degenerate for a plane.
struct LocalPlane {
  Vec3 centre = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double thickness = 0;  // the spread off the plane: the smallest eigenvalue's root
  double variation = 0;  // surface variation l0 / (l0 + l1 + l2): 0 on a plane
};
struct JetFits {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
  std::vector<LocalPlane> planes;
};
JetFits fit_jets(const std::vector<Vec3>& points, int neighbors, const std::string& source);

// The normals of fit_jets alone.
std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbors,
                                   const std::string& source);

// Near sharp features a neighbourhood spans both sides of the edge and its
// fitted normal rounds it off: each point whose neighbourhood is far from
// planar takes the normal of the most planar neighbourhood among its
// `neighbors` nearest points' whose plane passes through it (surface
// variation, Pauly et al. 2002). `fits` are fit_jets(points, neighbors);
// the signs of fits.normals are kept. Returns the normals and how many it replaced.
std::vector<Vec3> sharpen_normals(const std::vector<Vec3>& points, const JetFits& fits,
                                  int neighbors, std::size_t* replaced = nullptr);

// The neighbourhood size for normals on points whose noise (estimate_noise,
// solvers.h) is `noise` and average spacing `spacing`: `neighbors`, grown as
// (noise / (0.25 spacing))^2 up to kMaxNoiseNeighbors, so that the fit spans
// several times the noise.
constexpr int kMaxNoiseNeighbors = 100;
int noise_scaled_neighbors(double noise, double spacing, int neighbors);

// Orients `normals` consistently (flipping some) by propagating the
// orientation of the highest point (made to face +z) along a minimum spanning
// tree of the k-nearest-neighbour graph weighted by 1 - |n_i . n_j|
// (CGAL::mst_orient_normals, Hoppe et al. 1992), in each connected component
// of the graph from its own highest point. Returns the number of normals it
// flipped; `unreached` (when given) gets those left as they were: components
// of fewer than three points.
std::size_t orient_normals_mst(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                               int neighbors, std::size_t* unreached = nullptr);

// Splits the points into segments over which the normals' relative signs
// are reliable (k-nearest-neighbour links between normals within 26 degrees
// of parallel, each a step within 12 degrees of both tangent planes, so not
// across a thin part; strongest first) and makes each segment
// consistent, flipping some normals; segments of at most `neighbors` points
// then join a neighbouring one (through their most tangential link between
// normals within 60 degrees of parallel). Returns each point's segment (a point index).
// With `votes` (each point's, in [-1, 1], for its normal as given: visibility_votes),
// two segments whose mean votes are clear and contradict the link between them
// are not joined.
std::vector<int> orient_segments(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                                 int neighbors, const std::vector<double>* votes = nullptr);

// A segment whose mean vote (visibility_votes) is at least this is clear
// about its sign.
constexpr double kConfidentVote = 0.25;

// For each of the points listed in `samples`: the share of rays around +n that
// leave the points' bounding box without passing a point, less that around -n,
// in [-1, 1] (the open side is the outside). The rays march through a grid of
// cells of 1.5 average spacings, blocked by the cells within each point's mean
// distance to its 6 nearest (whose mean is that average spacing).
std::vector<double> visibility_votes(const std::vector<Vec3>& points,
                                     const std::vector<Vec3>& normals,
                                     const std::vector<std::size_t>& samples);

// Replaces the zero normals ((0, 0, 0): none, as some scanners write it) by
// ones estimated by jet fitting over `neighbors` nearest points, each turned to
// agree with the `neighbors` nearest given (non-zero) normals. Returns how many
// it replaced. Throws InputError naming `source` when there are fewer than
// kMinPointsForNormals points, std::invalid_argument when every normal is zero
// (points without normals: estimate and orient them instead).
std::size_t fill_missing_normals(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                                 int neighbors, const std::string& source);

// Flips `fraction` of the normals, chosen by `seed` (for the tests and
// bench/unoriented.sh: inputs whose orientation cannot be trusted).
void flip_random_normals(std::vector<Vec3>& normals, double fraction, std::uint64_t seed);

}  // namespace pdd
