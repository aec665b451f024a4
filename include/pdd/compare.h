// Metro-style distances between two triangle meshes (§4.2, Table 1; the
// accuracy columns of /work/shared/data/README.md): each surface is sampled
// densely and uniformly by area, and the exact distance from every sample to
// the other surface is measured. B is the reference (the ground truth): the
// relative numbers are divided by the bounding-box diagonal of B.
#pragma once

#include <pdd/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pdd {

struct CompareOptions {
  // The most samples compare_surfaces takes: about 70 bytes each while it runs.
  static constexpr std::size_t kMaxSamples = 100000000;
  std::size_t samples = 200000;  // area-uniform samples on each surface (as for the peers' table)
  double fscore_threshold = 0.005;  // τ of the F-score, relative to B's bounding-box diagonal
  std::uint64_t seed = 0;           // the sampling's random draws
};

// Distances from the samples of one surface to the other surface.
struct OneSidedDistance {
  std::size_t samples = 0;      // samples drawn on the source surface
  double max = 0;               // largest sample distance (one-sided Hausdorff)
  double mean = 0;              // mean sample distance
  double rms = 0;               // root mean square of the sample distances
  double within_threshold = 0;  // fraction of samples at distance <= τ
};

struct SurfaceDistance {
  OneSidedDistance a_to_b;  // samples of A, distances to B
  OneSidedDistance b_to_a;  // samples of B, distances to A
  double diagonal = 0;      // bounding-box diagonal of B, the reference for relative values
  double threshold = 0;     // τ in the meshes' units: CompareOptions::fscore_threshold * diagonal
  double hausdorff = 0;     // max(a_to_b.max, b_to_a.max)
  double chamfer_l1 = 0;    // (a_to_b.mean + b_to_a.mean) / 2
  double precision = 0;     // a_to_b.within_threshold: how much of A lies near B
  double recall = 0;        // b_to_a.within_threshold: how much of B is covered by A
  double fscore = 0;        // 2 precision recall / (precision + recall), 0 when both are 0

  // A distance of the meshes' units as a fraction of B's diagonal.
  double relative(double distance) const { return distance / diagonal; }
};

// The total area of the faces of `mesh`.
double surface_area(const TriangleMesh& mesh);

// Throws InputError "<source>: the mesh has no area (...)" when all faces of
// `mesh` are degenerate: such a mesh cannot be sampled or compared; and
// require_measurable's errors (quality.h) first.
void require_area(const TriangleMesh& mesh, const std::string& source);

// `count` points drawn uniformly by area on the faces of `mesh`: a face is
// chosen with probability proportional to its area, then a point uniformly in
// it. The same seed gives the same points. Throws std::invalid_argument when
// the mesh has no area or a face indexes a missing vertex.
std::vector<Vec3> sample_surface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed);

// Two-sided distances between the surfaces of `a` and `b` (B is the
// reference). Samples are drawn by sample_surface (seed for A, seed + 1 for
// B); the distance from a sample to the other surface is exact, found with
// an AABB tree on all faces of the other mesh (a face of zero area counts as
// the segment it is, but draws no samples); queries run in parallel and the
// result depends only on the meshes and the options. Throws
// std::invalid_argument when a mesh has no area, a face indexes a missing
// vertex, samples is 0 or more than kMaxSamples or fscore_threshold is
// negative.
SurfaceDistance compare_surfaces(const TriangleMesh& a, const TriangleMesh& b,
                                 const CompareOptions& options = {});

}  // namespace pdd
