// The progressive loop of §3.1 (Figure 3) and the domain strategies of §4.2.
#include <pdd/contour.h>
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/pipeline.h>
#include <pdd/quality.h>
#include <pdd/refine.h>

#include "common/cancellation.h"
#include "common/enum_names.h"
#include "pipeline/face_target.h"
#include "pipeline/memory_budget.h"
#include "pipeline/normals_step.h"
#include "pipeline/octree_domain.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <thread>

namespace pdd {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Eigen's thread count (its OpenMP sparse products) for the scope of a run:
// n if n > 0, then back to what it was.
class EigenThreads {
 public:
  explicit EigenThreads(int n) : saved_(Eigen::nbThreads()) {
    if (n > 0) Eigen::setNbThreads(n);
  }
  ~EigenThreads() { Eigen::setNbThreads(saved_); }
  EigenThreads(const EigenThreads&) = delete;
  EigenThreads& operator=(const EigenThreads&) = delete;

 private:
  int saved_;
};

// The centre of the points' bounding box (0.5 lo + 0.5 hi cannot overflow).
Vec3 bounding_box_centre(const std::vector<Vec3>& points) {
  if (points.empty()) return Vec3::Zero();
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return 0.5 * lo + 0.5 * hi;
}

// A caller's sizing field, given the isofacets of a run in coordinates
// relative to `centre` where they are in the caller's.
class TranslatedSizing : public SizingField {
 public:
  TranslatedSizing(std::shared_ptr<const SizingField> inner, const Vec3& centre)
      : inner_(std::move(inner)), centre_(centre) {}
  std::vector<double> target_areas(const Domain& domain,
                                   const std::vector<Isofacet>& facets) const override {
    return inner_->target_areas(domain, moved(facets));
  }
  std::vector<double> target_areas_marking_away(const Domain& domain,
                                                const std::vector<Isofacet>& facets,
                                                std::vector<char>& away) const override {
    return inner_->target_areas_marking_away(domain, moved(facets), away);
  }

 private:
  std::vector<Isofacet> moved(const std::vector<Isofacet>& facets) const {
    std::vector<Isofacet> out = facets;
    for (Isofacet& f : out) {
      for (Vec3& c : f.corners) c += centre_;
      f.centroid += centre_;
    }
    return out;
  }

  std::shared_ptr<const SizingField> inner_;
  Vec3 centre_;
};

// The options of a run in coordinates relative to `centre`: the caller's
// sizing field and iteration callback see the caller's coordinates.
ReconstructOptions relative_to(const ReconstructOptions& options, const Vec3& centre) {
  ReconstructOptions relative = options;
  if (options.custom_sizing)
    relative.custom_sizing = std::make_shared<TranslatedSizing>(options.custom_sizing, centre);
  if (options.on_iteration) {
    relative.on_iteration = [inner = options.on_iteration, centre](
                                const IterationStats& stats, const Domain& domain,
                                const TriangleMesh& isosurface) {
      Domain moved = domain;
      moved.translate(centre);
      TriangleMesh mesh = isosurface;
      for (Vec3& v : mesh.vertices) v += centre;
      inner(stats, moved, mesh);
    };
  }
  return relative;
}

std::shared_ptr<const SizingField> make_sizing(const PointSet& points,
                                               const ReconstructOptions& options) {
  if (options.custom_sizing) return options.custom_sizing;
  std::shared_ptr<const SizingField> field;
  if (options.sizing == SizingKind::kAdaptive) {
    field = adaptive_sizing(points, options.adaptive);
  } else {
    double area = options.target_area;
    if (area <= 0)
      area = options.target_edge_length > 0 ? area_for_edge_length(options.target_edge_length)
                                            : default_target_area(points);
    field = uniform_sizing(area);
  }
  if (options.away_from_data.max_factor == 1) return field;
  return coarser_away_from_data(std::move(field), points, options.away_from_data);
}

// The adaptive sizing at its default tolerance aims at this share of the
// uniform default's triangles: about its accuracy (Chamfer-L1 within 5 %)
// with fewer triangles (docs/benchmarks.md, "Adaptive sizing").
constexpr double kAdaptiveShare = 0.8;

// The output size a run aims at: the user's target_faces or, for the adaptive
// sizing at its default tolerance, kAdaptiveShare of the uniform default's.
detail::FaceTarget make_face_target(const PointSet& points, const ReconstructOptions& options) {
  const bool adaptive = options.sizing == SizingKind::kAdaptive && !options.custom_sizing;
  if (options.target_faces > 0)
    return detail::FaceTarget(static_cast<std::size_t>(options.target_faces), adaptive);
  if (adaptive && options.adaptive.tolerance <= 0) {
    ReconstructOptions uniform = options;
    uniform.sizing = SizingKind::kUniform;
    return detail::FaceTarget(make_sizing(points, uniform), kAdaptiveShare);
  }
  return {};
}

class Run {
 public:
  // `current` is where the run is, sent by `ask` (the progress callback, also
  // called from inside the stages); times are counted from `start`.
  Run(const PointSet& points, const std::vector<Vec3>& trim_samples,
      const ReconstructOptions& options, Progress& current, const std::function<bool()>& ask,
      Clock::time_point start)
      : points_(points),
        trim_samples_(trim_samples),
        current_(current),
        ask_(ask),
        options_(options),
        solver_(make_solver(options.solver)),
        budget_(options.max_memory, points.size(),
                options.sizing == SizingKind::kUniform && !options.custom_sizing &&
                    options.target_area <= 0 && options.target_edge_length <= 0 &&
                    options.target_faces == 0),
        face_target_(make_face_target(points, options)),
        rng_(options.seed),
        start_(start) {}

  // Figure 3, with optimizer passes on both sides of the refiner: after a
  // solve, with its solution (the isosurface the refiner then samples is
  // that of well-shaped tets), and on the refined domain before the next
  // solve, with the solution carried over to the new vertices. So every
  // solve runs on optimized tets, which CG converges fast on (Table 2), and
  // the last solve is the final one: no second solve on the finest domain.
  Result progressive() {
    Domain domain = initial_domain();
    std::shared_ptr<const SizingField> sizing = make_sizing(points_, options_);
    bool refined_last = false;  // the domain changed since it was last solved on
    for (int it = 1; it <= options_.max_iterations; ++it) {
      IterationStats stats;
      if (refined_last) optimize(domain, it, stats, options_.optimizer_rounds);
      solve(domain, it, stats);
      refined_last = false;
      const IsofacetAreaStats measured = within_budget(domain, sizing);
      record_sizing(measured, stats);
      bool converged = sizing_met(measured);
      const bool over_budget = !converged && !budget_.allows_refining(domain.num_vertices());
      if (!over_budget && !converged) {
        optimize(domain, it, stats, options_.optimizer_rounds_before_refining);
        report("refine", it, domain);
        const auto t = Clock::now();
        const RefinementStats refined = refine(domain, *sizing, rng_);
        stats.seconds_refine = seconds_since(t);
        stats.trisected = refined.trisected;
        stats.bisected = refined.bisected;
        stats.inserted_points = refined.inserted_points;
        refined_last = true;
        converged = refined.trisected + refined.bisected <
                    options_.min_refined_fraction * refined.crossing_tets;
      }
      const bool last = over_budget || converged || it == options_.max_iterations;
      if (last && !refined_last)
        return finish_with(std::move(domain), std::move(stats));
      result_.iterations.push_back(stats);
      if (last) break;
    }
    return finish(std::move(domain), /*optimize_first=*/refined_last, sizing.get());
  }

  // §4.2 (3): our refiner on the first solution, interpolated, no optimizer
  // but for one ASAP round before the final solve, as the paper's
  // non-optimized strategy does (§4.5: otherwise the solver fails).
  Result direct() {
    Domain domain = initial_domain();
    std::shared_ptr<const SizingField> sizing = make_sizing(points_, options_);
    IterationStats first;
    solve(domain, 1, first);
    result_.iterations.push_back(first);
    for (int it = 1; it <= options_.max_iterations; ++it) {
      if (sizing_met(within_budget(domain, sizing)) ||
          !budget_.allows_refining(domain.num_vertices()))
        break;
      report("refine", it, domain);
      const RefinementStats refined = refine(domain, *sizing, rng_);
      if (refined.trisected + refined.bisected <
          options_.min_refined_fraction * refined.crossing_tets)
        break;
    }
    OptimizerOptions asap_only = options_.optimizer;
    asap_only.mid_edge = false;
    optimize_domain(domain, asap_only);
    return finish(std::move(domain));
  }

  // §4.2 (2): all input points, then Delaunay refinement. Around unevenly
  // spaced samples a bound below 2 need not terminate (Shewchuk), so the
  // bound here is at least 2.
  Result input() {
    Domain domain = initial_domain();
    domain.insert(points_.points);
    domain.delaunay_refine(std::max(2.0, options_.domain.radius_edge_bound),
                           options_.domain.max_refinement_points);
    return finish(std::move(domain));
  }

  // §4.2 (1): all nodes of an octree refined from the input density.
  Result octree() {
    Domain domain = initial_domain();
    detail::insert_octree_nodes(domain, points_, options_.octree_depth);
    return finish(std::move(domain));
  }

 private:
  Domain initial_domain() {
    report("initialize", 0, Domain());
    return Domain::initial(points_, options_.domain);
  }

  // The isofacets against the sizing's targets, after scaling the sizing to
  // the output size asked for (if any), then coarsening it if the final domain
  // they predict would outgrow the memory budget.
  IsofacetAreaStats within_budget(const Domain& domain, std::shared_ptr<const SizingField>& sizing) {
    IsofacetAreaStats stats = isofacet_area_stats(domain, *sizing);
    if (face_target_.fit(domain, sizing, stats)) stats = isofacet_area_stats(domain, *sizing);
    return budget_.fit(sizing, stats) ? isofacet_area_stats(domain, *sizing) : stats;
  }

  // Calls the progress callback; a false answer cancels the run.
  void report(const char* stage, int iteration, const Domain& domain) {
    current_.stage = stage;
    current_.iteration = iteration;
    current_.vertices = domain.num_vertices();
    if (ask_ && !ask_()) throw detail::Cancelled{};
  }

  // Solves on the domain (warm-started from the current f) and measures the
  // isosurface; the contour is kept for the final iteration.
  void solve(Domain& domain, int iteration, IterationStats& stats) {
    stats.iteration = iteration;
    report("solve", iteration, domain);
    auto t = Clock::now();
    contour_ = IsoSurface();  // the last solve's: freed for the solve's peak of memory
    const std::vector<double> warm = domain.f();
    // The solve's system and multigrid are the run's peak of memory; the
    // triangulation is rebuilt from the tets when the optimizer next needs it.
    solver_->release_triangulation_in_next_solve();
    domain.set_f(solver_->solve(domain, points_, &warm));
    stats.seconds_solve = seconds_since(t);
    stats.solver = solver_->stats();

    report("contour", iteration, domain);
    t = Clock::now();
    contour_ = marching_tetrahedra(domain.mesh(), domain.f());
    stats.seconds_contour = seconds_since(t);
    measure(domain, stats);
    if (options_.on_iteration) options_.on_iteration(stats, domain, contour_.mesh);
  }

  void optimize(Domain& domain, int iteration, IterationStats& stats, int rounds) {
    contour_ = IsoSurface();  // of the domain before the moves: freed for the optimizer's peak
    const auto t = Clock::now();
    for (int round = 0; round < rounds; ++round) {
      report("optimize", iteration, domain);
      const OptimizerReport r = optimize_domain(domain, options_.optimizer);
      stats.optimizer_cg_iterations += r.cg_iterations;
      stats.rejected_moves += r.rejected_moves;
    }
    stats.seconds_optimize += seconds_since(t);
  }

  // The final isosurface without its small and open components, then with
  // the flips and needle collapses of the clean-up; the final iteration's
  // triangle statistics then describe the mesh returned.
  void clean_up(const Domain& domain, IterationStats& stats) {
    report("clean-up", stats.iteration, domain);
    const auto t = Clock::now();
    if (options_.min_component_edges > 0)
      stats.open_components = remove_open_components(result_.mesh);
    stats.small_components = remove_small_components(result_.mesh, options_.min_component_edges);
    stats.unsupported_components =
        remove_unsupported_components(result_.mesh, points_.points, options_.min_component_samples);
    detail::poll();
    stats.handles = cut_unsupported_handles(result_.mesh, points_, options_.handles);
    detail::poll();
    result_.trim = trim_to_samples(result_.mesh, trim_samples_, options_.trim);
    detail::poll();
    if (options_.cleanup)
      stats.cleanup = cleanup_isosurface(result_.mesh, options_.cleanup_options);
    if (options_.handles.enabled) stats.handles.handles += cut_triangle_waists(result_.mesh);
    stats.boundary_edges = count_boundary_edges(result_.mesh);
    stats.seconds_cleanup = seconds_since(t);
    stats.isovertices = result_.mesh.vertices.size();
    stats.triangles = result_.mesh.faces.size();
    const TriangleQuality q = triangle_quality(result_.mesh);
    stats.mean_min_angle = q.mean_min_angle;
    stats.fraction_below_30 = q.fraction_below_30;
  }

  // Table 1's columns for the current contour.
  void measure(const Domain& domain, IterationStats& stats) const {
    std::vector<char> near(domain.num_vertices(), 0);
    for (int t : contour_.facet_tet)
      for (int v : domain.tets()[t]) near[v] = 1;
    stats.vertices = domain.num_vertices();
    stats.vertices_near_isosurface = static_cast<std::size_t>(std::count(near.begin(), near.end(), 1));
    stats.parsimony = stats.vertices ? static_cast<double>(stats.vertices_near_isosurface) /
                                           static_cast<double>(stats.vertices)
                                     : 0.0;
    stats.isovertices = contour_.mesh.vertices.size();
    stats.triangles = contour_.mesh.faces.size();
    const TriangleQuality q = triangle_quality(contour_.mesh);
    stats.mean_min_angle = q.mean_min_angle;
    stats.fraction_below_30 = q.fraction_below_30;
  }

  // The final solve on the final domain (optimized first if asked), and
  // its isosurface, measured against `sizing` when there is one.
  Result finish(Domain domain, bool optimize_first = false, const SizingField* sizing = nullptr) {
    const int last = result_.iterations.empty() ? 1 : result_.iterations.back().iteration + 1;
    IterationStats stats;
    if (optimize_first) optimize(domain, last, stats, options_.optimizer_rounds);
    solve(domain, last, stats);
    if (sizing) record_sizing(isofacet_area_stats(domain, *sizing), stats);
    return finish_with(std::move(domain), std::move(stats));
  }

  static void record_sizing(const IsofacetAreaStats& measured, IterationStats& stats) {
    stats.crossing_tets = measured.count;
    stats.mean_area_ratio = measured.mean_ratio;
    stats.above_4 = measured.above_4;
    stats.away_from_data = measured.away;
    stats.above_4_away_from_data = measured.above_4_away;
  }

  // The result, with `stats` (of the solve whose contour is contour_) as its
  // final iteration.
  Result finish_with(Domain domain, IterationStats stats) {
    result_.iterations.push_back(std::move(stats));
    result_.mesh = std::move(contour_.mesh);
    clean_up(domain, result_.iterations.back());
    result_.domain = std::move(domain);
    result_.budget = budget_.report();
    result_.seconds = seconds_since(start_);
    return std::move(result_);
  }

  const PointSet& points_;
  // The points the trim keeps the surface near: the input's, outliers included
  // (a point the outlier test dropped that the surface still passes through,
  // as at a scan's sparse edge, keeps its surface; a stray's disc is an island).
  const std::vector<Vec3>& trim_samples_;
  Progress& current_;
  const std::function<bool()>& ask_;
  const ReconstructOptions& options_;
  std::unique_ptr<ImplicitSolver> solver_;  // every solve, so that its multigrid keeps the levels
  detail::VertexBudget budget_;
  detail::FaceTarget face_target_;
  std::mt19937_64 rng_;
  Clock::time_point start_;
  IsoSurface contour_;
  Result result_;
};

}  // namespace

namespace {

constexpr EnumNames<DomainStrategy> kStrategies[] = {{DomainStrategy::kProgressive, "progressive"},
                                                     {DomainStrategy::kDirect, "direct"},
                                                     {DomainStrategy::kInput, "input"},
                                                     {DomainStrategy::kOctree, "octree"}};
constexpr EnumNames<SizingKind> kSizings[] = {{SizingKind::kUniform, "uniform"},
                                              {SizingKind::kAdaptive, "adaptive"}};
constexpr EnumNames<NormalsMode> kNormalsModes[] = {{NormalsMode::kKeep, "keep"},
                                                    {NormalsMode::kOrient, "orient"},
                                                    {NormalsMode::kEstimate, "estimate"}};
constexpr EnumNames<Orientation> kOrientations[] = {{Orientation::kMst, "mst"},
                                                    {Orientation::kSpectral, "spectral"},
                                                    {Orientation::kVisibility, "visibility"}};

}  // namespace

DomainStrategy parse_domain_strategy(const std::string& name) {
  return parse_enum(name, kStrategies, "domain strategy");
}
std::string to_string(DomainStrategy strategy) { return enum_name(strategy, kStrategies); }

SizingKind parse_sizing_kind(const std::string& name) {
  return parse_enum(name, kSizings, "sizing");
}

NormalsMode parse_normals_mode(const std::string& name) {
  return parse_enum(name, kNormalsModes, "normals mode");
}
std::string to_string(NormalsMode mode) { return enum_name(mode, kNormalsModes); }

Orientation parse_orientation(const std::string& name) {
  return parse_enum(name, kOrientations, "orientation");
}
std::string to_string(Orientation orientation) { return enum_name(orientation, kOrientations); }

int max_threads() {
  return 4 * static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

namespace {
Result run_stages(const PointSet& points, const ReconstructOptions& options, Progress& current,
                  const std::function<bool()>& ask, Clock::time_point start);
}  // namespace

Result reconstruct(const PointSet& points, const ReconstructOptions& options) {
  if (options.max_iterations < 1)
    throw InputError("reconstruct: at least one iteration is needed, got " +
                     std::to_string(options.max_iterations));
  if (options.optimizer_rounds < 0 || options.optimizer_rounds_before_refining < 0)
    throw InputError("reconstruct: optimizer rounds must be >= 0, got " +
                     std::to_string(options.optimizer_rounds) + " and " +
                     std::to_string(options.optimizer_rounds_before_refining));
  if (options.threads < 0 || options.threads > max_threads())
    throw InputError("reconstruct: threads must be from 0 to " + std::to_string(max_threads()) +
                     ", got " + std::to_string(options.threads));
  if (options.target_faces < 0)
    throw InputError("reconstruct: the target face count must be >= 0, got " +
                     std::to_string(options.target_faces));
  if (options.target_faces > 0 &&
      (options.target_edge_length > 0 || options.target_area > 0 || options.custom_sizing))
    throw InputError(
        "reconstruct: --target-faces sets the size; give it without --target-edge, "
        "--target-area or a sizing field of your own");
  if (!(options.min_component_edges >= 0) || !std::isfinite(options.min_component_edges))
    throw InputError("reconstruct: the smallest component size must be >= 0 edge lengths, got " +
                     std::to_string(options.min_component_edges));
  std::optional<tbb::global_control> threads;
  if (options.threads > 0)
    threads.emplace(tbb::global_control::max_allowed_parallelism,
                    static_cast<std::size_t>(options.threads));
  const EigenThreads eigen_threads(options.threads);
  const auto start = Clock::now();
  // Where the run is: set by each stage's report, and sent again from inside
  // the long loops (detail::poll) so that a cancellation is heard within a stage.
  Progress current;
  current.stage = "initialize";
  std::function<bool()> ask;
  if (options.progress)
    ask = [&] {
      current.elapsed_seconds = seconds_since(start);
      return options.progress(current);
    };
  // One callable for every call, as the user's callback may keep state.
  const detail::PollScope poll_scope(ask, options.progress_interval);
  try {
    return run_stages(points, options, current, ask, start);
  } catch (const detail::Cancelled&) {
  }
  Result cancelled;
  cancelled.cancelled = true;
  return cancelled;
}

namespace {

// reconstruct() once its options are checked: outliers, normals, then the
// domain strategy's stages.
Result run_stages(const PointSet& points, const ReconstructOptions& options, Progress& current,
                  const std::function<bool()>& ask, Clock::time_point start) {
  // Stray points first: they would become blobs, and skew the normals' estimation.
  OutlierReport outliers;
  const std::vector<char> stray = find_outliers(points.points, options.outliers, &outliers);
  PointSet without_outliers;
  if (outliers.removed > 0) {
    without_outliers = points;
    std::vector<char> keep(stray.size());
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !stray[i];
    without_outliers.keep(keep);
    if (without_outliers.size() < ValidationOptions{}.min_points)
      throw InputError(options.source + ": only " + std::to_string(without_outliers.size()) +
                       " points are left once the " + std::to_string(outliers.removed) +
                       " outliers are dropped; lower or turn off --outliers");
  }
  const PointSet& kept = outliers.removed > 0 ? without_outliers : points;
  PointSet samples;  // the points with the attributes the output carries
  samples.attributes = select_attributes(kept, options.attributes, options.source);
  // Normals estimated or oriented first when they are missing or untrusted.
  PointSet with_new_normals;
  NormalsReport normals;
  const PointSet& input = detail::prepare_normals(kept, options, with_new_normals, normals);
  if (input.normals.size() != input.points.size())
    throw InputError("reconstruct: " + std::to_string(input.normals.size()) + " normals for " +
                     std::to_string(input.points.size()) + " points");
  // The run works in coordinates relative to the input's bounding-box centre,
  // its scale untouched (absolute options such as the target edge keep their
  // meaning): far from the origin, as georeferenced scans are, it keeps the
  // precision it has at the origin, and a translated input gives the same
  // output, translated, up to rounding.
  const Vec3 centre = bounding_box_centre(input.points);
  PointSet relative;
  relative.points = input.points;
  relative.normals = input.normals;
  for (Vec3& p : relative.points) p -= centre;
  ReconstructOptions resolved = relative_to(options, centre);
  // The input's noise for the automatic value weight of SSD, the screened
  // Poisson solver or the spectral solver, once for all the solves.
  SsdOptions& ssd = resolved.solver.ssd;
  PoissonOptions& poisson = resolved.solver.poisson;
  const SolverKind kind = resolved.solver.kind;
  if (kind == SolverKind::kSsd && ssd.alpha == 0 && ssd.noise < 0)
    ssd.noise = estimate_noise(relative);
  if (kind == SolverKind::kPoisson && poisson.screened && poisson.alpha == 0 && poisson.noise < 0)
    poisson.noise = estimate_noise(relative);
  SpectralOptions& spectral = resolved.solver.spectral;
  if (kind == SolverKind::kSpectral && spectral.alpha == 0) {
    if (spectral.noise < 0) spectral.noise = estimate_noise(relative);
    if (spectral.spacing < 0) spectral.spacing = average_spacing(relative);
  }
  const double noise = kind == SolverKind::kSsd       ? ssd.noise
                       : kind == SolverKind::kPoisson ? poisson.noise
                                                      : spectral.noise;
  std::vector<Vec3> trim_samples;  // the input's points, outliers included (Run::trim_samples_)
  if (options.trim.distance > 0) {
    trim_samples = points.points;
    for (Vec3& p : trim_samples) p -= centre;
  }
  Run run(relative, trim_samples, resolved, current, ask, start);
  Result result = [&] {
    switch (resolved.strategy) {
      case DomainStrategy::kProgressive: return run.progressive();
      case DomainStrategy::kDirect: return run.direct();
      case DomainStrategy::kInput: return run.input();
      case DomainStrategy::kOctree: return run.octree();
    }
    throw InputError("reconstruct: unknown domain strategy");
  }();
  if (!samples.attributes.empty()) {
    samples.points = std::move(relative.points);
    result.mesh.attributes = interpolate_attributes(samples, result.mesh.vertices);
  }
  for (Vec3& v : result.mesh.vertices) v += centre;
  result.domain.translate(centre);
  result.outliers = outliers;
  result.noise = std::max(0.0, noise);
  result.normals = normals;
  return result;
}

}  // namespace

}  // namespace pdd
