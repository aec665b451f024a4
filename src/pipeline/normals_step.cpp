// Estimation and orientation of the input's normals before the run.
#include "pipeline/normals_step.h"

#include <pdd/errors.h>
#include <pdd/normals.h>
#include <pdd/sizing.h>

#include "common/cancellation.h"

#include <algorithm>
#include <chrono>

namespace pdd::detail {
namespace {

// Design (b) of issue 17. A coarse progressive run of the spectral solver,
// which ignores the normals' signs (Eq. 16), gives f < 0 inside; each normal
// is turned towards increasing f, comparing f a short step on either side of
// its sample. Coarse (4x the target edge, a few seconds), that is right over
// most of the surface but not across parts thinner than its tets; so it only
// votes: the segments over which the normals' relative signs are reliable
// (orient_segments) each take the sign of their majority.
std::size_t orient_by_spectral_vote(PointSet& input, const ReconstructOptions& options,
                                    std::size_t& segments) {
  const std::vector<Vec3> initial = input.normals;
  const std::vector<int> segment =
      orient_segments(input.points, input.normals, options.normal_neighbors);

  ReconstructOptions coarse = options;
  coarse.normals = NormalsMode::kKeep;
  coarse.outliers.ratio = 0;  // already dropped
  coarse.trim = {};
  coarse.attributes = "none";
  coarse.solver.kind = SolverKind::kSpectral;
  coarse.sizing = SizingKind::kUniform;
  coarse.custom_sizing = nullptr;
  coarse.target_area = 0;
  const double edge = 4 * (options.target_edge_length > 0 ? options.target_edge_length
                                                         : default_target_edge(input));
  coarse.target_edge_length = edge;
  coarse.cleanup = false;
  coarse.min_component_edges = 0;
  coarse.on_iteration = nullptr;
  if (options.progress)
    coarse.progress = [&progress = options.progress](const Progress& p) {
      Progress orient = p;
      orient.stage = "orient";
      return progress(orient);
    };
  const Result run = reconstruct(input, coarse);
  if (run.cancelled) throw Cancelled{};
  const Domain& domain = run.domain;
  const double step = 0.25 * edge;
  std::vector<double> vote(input.size(), 0.0);
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Vec3& p = input.points[i];
    const Vec3& n = input.normals[i];
    const double outside = domain.interpolate(p + step * n, domain.f());
    const double inside = domain.interpolate(p - step * n, domain.f());
    vote[segment[i]] += outside > inside ? 1 : -1;
  }
  segments = 0;
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < input.size(); ++i) {
    segments += segment[i] == static_cast<int>(i);
    if (vote[segment[i]] < 0) input.normals[i] = -input.normals[i];
    flipped += input.normals[i].dot(initial[i]) < 0;
  }
  return flipped;
}

}  // namespace

const PointSet& prepare_normals(const PointSet& points, const ReconstructOptions& options,
                                PointSet& storage, NormalsReport& report) {
  const bool estimate = !points.has_normals() || options.normals == NormalsMode::kEstimate;
  const bool zeros = !estimate && std::any_of(points.normals.begin(), points.normals.end(),
                                              [](const Vec3& n) { return n.squaredNorm() == 0; });
  if (!estimate && !zeros && options.normals == NormalsMode::kKeep) return points;
  const auto start = std::chrono::steady_clock::now();
  storage.points = points.points;
  storage.normals = estimate
                        ? estimate_normals(points.points, options.normal_neighbors, options.source)
                        : points.normals;
  if (zeros)
    report.filled = fill_missing_normals(storage.points, storage.normals,
                                         options.normal_neighbors, options.source);
  if (!estimate && options.normals == NormalsMode::kKeep) {
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return storage;
  }
  report.estimated = estimate;
  report.oriented = true;
  report.orientation = options.orientation;
  switch (options.orientation) {
    case Orientation::kMst:
      report.flipped = orient_normals_mst(storage.points, storage.normals,
                                          options.normal_neighbors, &report.unreached);
      break;
    case Orientation::kSpectral:
      report.flipped = orient_by_spectral_vote(storage, options, report.segments);
      break;
  }
  report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return storage;
}

}  // namespace pdd::detail

namespace pdd {

PointSet prepare_normals(const PointSet& points, const ReconstructOptions& options,
                         NormalsReport* report) {
  PointSet storage;
  NormalsReport done;
  try {
    const PointSet& prepared = detail::prepare_normals(points, options, storage, done);
    if (report) *report = done;
    return &prepared == &points ? points : storage;
  } catch (const detail::Cancelled&) {
    throw InputError(options.source + ": the orientation's coarse run was cancelled");
  }
}

}  // namespace pdd
