// The progressive reconstruction of §3.1 (Figure 3): initial domain, then
// iterations of solve -> optimize -> refine, then a final solve on the
// optimized domain and marching tetrahedra. The iterations stop when the
// sizing field is met (refine.h, sizing_met), when a refinement pass splits
// few tets or at max_iterations, and never outgrow the memory budget. Also the three other domain
// strategies of §4.2, for comparison.
#pragma once

#include <pdd/contour.h>
#include <pdd/domain.h>
#include <pdd/optimize.h>
#include <pdd/outliers.h>
#include <pdd/sizing.h>
#include <pdd/solvers.h>
#include <pdd/types.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pdd {

// §4.2: how the domain on which the final solve happens is built.
enum class DomainStrategy {
  kProgressive,  // ours: solve -> optimize -> refine iterations
  kDirect,       // our refiner on the interpolated first solution, no optimizer, one final solve
  kInput,        // all input points + Delaunay refinement, one solve
  kOctree,       // all nodes of an octree refined from the input density, one solve
};
DomainStrategy parse_domain_strategy(const std::string& name);  // InputError when unknown
std::string to_string(DomainStrategy strategy);

// What the run does with the input's normals (normals.h). Missing normals are
// always estimated.
enum class NormalsMode {
  kKeep,      // use the given normals as they are
  kOrient,    // keep their directions, orient them anew (their signs cannot be trusted)
  kEstimate,  // replace them by estimated ones, oriented
};
NormalsMode parse_normals_mode(const std::string& name);  // InputError when unknown
std::string to_string(NormalsMode mode);

// How estimated or re-oriented normals get their signs.
enum class Orientation {
  kMst,         // propagation along a minimum spanning tree (normals.h, the peers' method)
  kSpectral,    // segments of reliably consistent normals, each turned by the majority of
                // its points along the gradient of a coarse run of the spectral solver
                // (§3.5, Eq. 16-17), which needs no orientation
  kVisibility,  // the same segments, each turned by the majority of its points towards
                // the side from which more rays escape past the points to infinity
};
Orientation parse_orientation(const std::string& name);  // InputError when unknown
std::string to_string(Orientation orientation);

enum class SizingKind { kUniform, kAdaptive };
SizingKind parse_sizing_kind(const std::string& name);  // InputError when unknown

// Where the run is, for the progress callback.
struct Progress {
  std::string stage;        // "initialize", "solve", "optimize", "refine", "contour"
  int iteration = 0;        // 1-based; 0 during initialization, the final solve is last + 1
  std::size_t vertices = 0;
  double elapsed_seconds = 0;
};

// Returning false from the callback stops the run cleanly (Result::cancelled).
using ProgressCallback = std::function<bool(const Progress&)>;

struct IterationStats;
class Domain;
// Called after each solve with the domain, f and its isosurface (Figure 7).
using IterationCallback =
    std::function<void(const IterationStats&, const Domain&, const TriangleMesh& isosurface)>;

struct ReconstructOptions {
  DomainStrategy strategy = DomainStrategy::kProgressive;
  NormalsMode normals = NormalsMode::kKeep;      // missing normals are estimated whatever this is
  Orientation orientation = Orientation::kVisibility;  // of estimated or re-oriented normals
  int normal_neighbors = 18;                     // k of the estimation (grown on noisy points:
                                                 // noise_scaled_neighbors, normals.h) and the MST
  std::string source = "points";                 // names the input in error messages
  OutlierOptions outliers;     // stray points dropped before everything else (outliers.h)
  DomainOptions domain;        // §3.2: sphere 1.4 r, 100 points, radius-edge 1.3
  SolverOptions solver;        // §3.5: SSD by default
  OptimizerOptions optimizer;  // §3.3: lambda_a = 60, lambda_m = 3 (optimize.h)
  // Optimizer passes (§3.3) per iteration: on each refined domain before it is solved on, with
  // the previous solution carried over (so that every solve runs on optimized tets), and after
  // a solve, with its solution, before the domain is refined (docs/benchmarks.md, "Loop order").
  int optimizer_rounds = 2;
  int optimizer_rounds_before_refining = 1;
  double min_component_edges = 4;  // components of the final isosurface smaller than this many
                                   // mean edge lengths across are removed, and so are those
                                   // cut open by the domain's boundary but the largest
                                   // (contour.h, remove_small_components and
                                   // remove_open_components); 0: all kept
  int min_component_samples = 10;  // components but the largest nearest to fewer input points,
                                   // or to a tenth of the mesh's points per area, are removed:
                                   // blobs and bubbles around stray points (contour.h,
                                   // remove_unsupported_components); 0: all kept
  HandleOptions handles;       // spurious handles cut from the final surface (contour.h,
                               // cut_unsupported_handles); handles.enabled = false keeps them
  TrimOptions trim;            // distance 0 (the default): the closed surface; otherwise cut to
                               // the samples' support after the small components went (contour.h)
  // The point attributes the output's vertices carry (contour.h, interpolate_attributes):
  // "colors" (red, green, blue, alpha when the points have them), "all", "none", or names
  // separated by commas; parse_attribute_selection checks the text.
  std::string attributes = "colors";
  bool cleanup = true;         // flips and needle collapses on the final isosurface (contour.h);
                               // not part of the paper, docs/benchmarks.md "Isosurface clean-up"
  CleanupOptions cleanup_options;

  SizingKind sizing = SizingKind::kUniform;
  double target_area = 0;         // uniform: the target isofacet area; 0: from target_edge_length
  double target_edge_length = 0;  // uniform: the target edge; 0: default_target_edge (sizing.h)
  // About this many output triangles (0: off): the sizing (uniform or adaptive)
  // is scaled to it from the isosurface of the early iterations; not with a
  // target edge or area, or a custom sizing.
  int target_faces = 0;
  AdaptiveSizingOptions adaptive;  // adaptive sizing of §3.4
  // Library only: overrides `sizing` when set. The run works in coordinates
  // relative to the input's bounding-box centre (reconstruct()); the field is
  // given the isofacets in the input's coordinates, the Domain in the run's.
  std::shared_ptr<const SizingField> custom_sizing;
  DataDistanceOptions away_from_data;  // uniform and adaptive: coarser where no input is near
                                       // (sizing.h; max_factor = 1 turns it off)

  int max_iterations = 12;             // solve-optimize-refine iterations at most
  std::size_t max_memory = 0;  // bytes the run may use (0: 3/4 of the memory available at its
                               // start); the domain's vertex budget follows, and a run whose
                               // sizing would outgrow it coarsens the sizing (MemoryBudget)
  double min_refined_fraction = 0.02;  // stop once a refinement pass splits fewer crossing tets
  int octree_depth = 0;                // kOctree: 0 = finest cells about the input spacing
  std::uint64_t seed = 0;              // the refiner's random draws (rule 5 of §3.4)
  int threads = 0;                     // 0 = all cores
  ProgressCallback progress;           // optional
  // Inside a stage the callback is called again (same stage) at most every
  // this many seconds, from the long loops, so that returning false stops
  // the run within a fraction of a second; 0: at every loop's check.
  double progress_interval = 0.1;
  IterationCallback on_iteration;      // optional
};

// Statistics of one iteration (the columns of Table 1 and Figure 15).
struct IterationStats {
  int iteration = 0;
  std::size_t vertices = 0;                  // (3) of Table 1, after the solve
  std::size_t vertices_near_isosurface = 0;  // (2): vertices of tets crossed by f = 0
  double parsimony = 0;                      // (4) = (2) / (3)
  std::size_t isovertices = 0;               // (1): vertices of the isosurface
  std::size_t triangles = 0;
  SolverStats solver;
  int optimizer_cg_iterations = 0;
  int rejected_moves = 0;
  int trisected = 0, bisected = 0, inserted_points = 0;
  // The isofacets against the sizing field after the solve, which the loop
  // stops on (refine.h, sizing_met): their count (the tets f = 0 crosses), the
  // mean of their area over their target, how many are 4x their target or
  // more, and how many of each lie away from the data (the sizing's coarsened
  // targets), where the 4x ones do not count. Progressive strategy only.
  int crossing_tets = 0;
  double mean_area_ratio = 0;
  int above_4 = 0;
  int away_from_data = 0;
  int above_4_away_from_data = 0;
  double mean_min_angle = 0;     // of the isosurface's triangles, degrees
  double fraction_below_30 = 0;  // of the isosurface's triangles
  double seconds_solve = 0, seconds_optimize = 0, seconds_refine = 0, seconds_contour = 0;
  // The final iteration only: the small and the open components removed and,
  // when ReconstructOptions::cleanup is on, the clean-up; its isovertex and
  // triangle counts and angles above are those of the mesh returned.
  RemovedComponents small_components;
  RemovedComponents open_components;
  RemovedComponents unsupported_components;
  CutHandles handles;
  CleanupReport cleanup;
  // Edges of one face in the mesh returned: where the surface reaches the
  // domain's boundary (points that enclose no volume), or the trim's rim.
  std::size_t boundary_edges = 0;
  double seconds_cleanup = 0;
};

// The memory budget of a run and what it did to the sizing. The final
// domain is predicted after each solve from the isofacets' areas against
// their targets (about 0.6-0.7 domain vertices per target-sized isofacet);
// when the prediction exceeds the vertex budget, every target area is
// multiplied so that it fits.
struct MemoryBudget {
  std::size_t bytes = 0;                // the budget (ReconstructOptions::max_memory or default)
  std::size_t vertices = 0;             // the domain's vertex budget that follows
  std::size_t predicted_vertices = 0;   // the largest final domain predicted at the asked sizing
  double coarsening = 1;                // factor of the target areas (1: none; edges: its root)
  bool refinement_stopped = false;      // the domain reached 3/4 of the vertex budget
  // With the default sizing, the domain also stays in proportion to the input: at most
  // about 60 output triangles per point (plus 5000), whatever the memory allows.
  std::size_t input_vertices = 0;       // that cap in domain vertices (0: none, a sizing was asked)
  bool limited_by_input = false;        // the vertex budget is that cap, not the memory's
};

// Parses a memory size: a positive number of bytes with an optional unit
// K, M, G or T (powers of 1024; "KB", "MiB" and the like too), e.g. "8G",
// "500M", "1.5GiB". InputError naming `what` when it is not one.
std::size_t parse_memory_size(const std::string& text, const std::string& what = "--max-memory");

// What the run did to the input's normals.
struct NormalsReport {
  bool estimated = false;       // by jet fitting (the input had none, or NormalsMode::kEstimate)
  bool oriented = false;        // by `orientation` (estimated, or NormalsMode::kOrient)
  Orientation orientation = Orientation::kVisibility;
  std::size_t flipped = 0;      // normals whose sign the orientation changed
  std::size_t unreached = 0;    // kMst: normals the tree did not reach (left as they were)
  std::size_t segments = 0;     // kSpectral, kVisibility: segments of consistent normals
  std::size_t unclear = 0;      // kVisibility: points of segments whose visibility was unclear
                                // and that took a coarse spectral run's vote (one-sided scans)
  std::size_t sharpened = 0;    // estimated normals taken from a neighbour's flatter neighbourhood
                                // (sharp features: sharpen_normals, normals.h)
  std::size_t filled = 0;       // zero normals (none given) replaced by estimated ones
  int neighbors = 0;            // k of the orientation's jets: normal_neighbors, grown on noisy
                                // points (noise_scaled_neighbors, normals.h)
  bool smoothed = false;        // noisy points: estimated and oriented on their jets' projection
  double seconds = 0;
};

// Checks and normalizes an attribute selection (ReconstructOptions::attributes):
// "colors", "all", "none" or a comma-separated list of property names (letters,
// digits, '_'; "colors" may be one of them). InputError "--attributes: ..." otherwise.
std::string parse_attribute_selection(const std::string& text);

// The attributes of `points` that `selection` names, in the points' order.
// InputError naming `source` when it names a property the points lack.
std::vector<Attribute> select_attributes(const PointSet& points, const std::string& selection,
                                         const std::string& source);

struct Result {
  TriangleMesh mesh;  // the isosurface of the final solve, outward-facing, without its small
                      // components, trimmed if asked, cleaned up unless ReconstructOptions::cleanup
                      // is off, with the selected attributes at its vertices
  Domain domain;      // the final domain, f = the final solution
  std::vector<IterationStats> iterations;  // the last entry is the final solve
  double noise = 0;  // SSD or screened Poisson with the automatic value weight:
                     // estimate_noise(points) (solvers.h); otherwise 0. The weight of each
                     // solve is in its SolverStats.
  MemoryBudget budget;
  OutlierReport outliers;  // the points dropped as outliers before the run
  TrimReport trim;         // what the trim cut (trimmed = false: the surface is closed)
  NormalsReport normals;
  double seconds = 0;
  bool cancelled = false;  // the progress callback returned false: mesh is empty
};

// The depth of the octree-based domain (DomainStrategy::kOctree with
// octree_depth = 0): its finest cells are about the input's average spacing,
// over a cube 5 % larger than the bounding box's largest side.
int default_octree_depth(const PointSet& points);

// The input with the normals a run would use (its first step): `points` as
// they are, or with normals estimated and/or oriented as options.normals,
// orientation and normal_neighbors say. For `pdd normals` and
// pdd.estimate_normals. InputError when normals cannot be estimated.
PointSet prepare_normals(const PointSet& points, const ReconstructOptions& options,
                         NormalsReport* report = nullptr);

// The most worker threads a run may ask for (ReconstructOptions::threads):
// 4 times the hardware threads. More only slow a run down, and past a few
// hundred the thread libraries fail to create them.
int max_threads();

// Reconstructs a closed surface from `points`. The run works in coordinates
// relative to the points' bounding-box centre and returns the mesh and the
// domain in the points' own, so that translated points give the same output,
// translated, up to rounding. Throws InputError for bad input or options,
// SolverError when a solve fails.
Result reconstruct(const PointSet& points, const ReconstructOptions& options = {});

}  // namespace pdd
