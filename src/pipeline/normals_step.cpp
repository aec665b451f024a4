// Estimation and orientation of the input's normals before the run.
#include "pipeline/normals_step.h"

#include <pdd/errors.h>
#include <pdd/normals.h>
#include <pdd/sizing.h>

#include <chrono>

namespace pdd::detail {
namespace {

// A coarse progressive run with the current normals gives f < 0 inside; each
// normal is then turned towards increasing f, comparing f a short step on
// either side of its sample (the re-estimation of iterative Poisson
// reconstruction, once, at twice the target edge).
std::size_t orient_along_coarse_run(PointSet& input, const ReconstructOptions& options,
                                    SolverKind solver, double coarsening = 2) {
  ReconstructOptions coarse = options;
  coarse.normals = NormalsMode::kKeep;
  coarse.solver.kind = solver;
  coarse.sizing = SizingKind::kUniform;
  coarse.custom_sizing = nullptr;
  coarse.target_area = 0;
  const double edge = coarsening * (options.target_edge_length > 0 ? options.target_edge_length
                                                          : default_target_edge(input));
  coarse.target_edge_length = edge;
  coarse.cleanup = false;
  coarse.min_component_edges = 0;
  coarse.on_iteration = nullptr;
  if (options.progress)
    coarse.progress = [progress = options.progress](const Progress& p) {
      Progress orient = p;
      orient.stage = "orient";
      return progress(orient);
    };
  const Result run = reconstruct(input, coarse);
  if (run.cancelled) throw OrientationCancelled{};
  const Domain& domain = run.domain;
  const double step = 0.25 * edge;
  std::size_t flipped = 0;
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Vec3& p = input.points[i];
    Vec3& n = input.normals[i];
    const double outside = domain.interpolate(p + step * n, domain.f());
    const double inside = domain.interpolate(p - step * n, domain.f());
    if (outside < inside) {
      n = -n;
      ++flipped;
    }
  }
  return flipped;
}

}  // namespace

const PointSet& prepare_normals(const PointSet& points, const ReconstructOptions& options,
                                PointSet& storage, NormalsReport& report) {
  const bool estimate = !points.has_normals() || options.normals == NormalsMode::kEstimate;
  if (!estimate && options.normals == NormalsMode::kKeep) return points;
  const auto start = std::chrono::steady_clock::now();
  storage.points = points.points;
  storage.normals = estimate ? estimate_normals(points.points, options.normal_neighbors, options.source)
                             : points.normals;
  report.estimated = estimate;
  report.oriented = true;
  report.orientation = options.orientation;
  switch (options.orientation) {
    case Orientation::kMst:
      report.flipped = orient_normals_mst(storage.points, storage.normals,
                                          options.normal_neighbors, &report.unreached);
      break;
    case Orientation::kSpectral:
      report.flipped = orient_along_coarse_run(storage, options, SolverKind::kSpectral);
      break;
    case Orientation::kMstSolve: {
      std::vector<Vec3> initial = storage.normals;
      orient_normals_mst(storage.points, storage.normals, options.normal_neighbors,
                         &report.unreached);
      orient_along_coarse_run(storage, options, SolverKind::kSsd);
      report.flipped = 0;
      for (std::size_t i = 0; i < initial.size(); ++i)
        report.flipped += initial[i].dot(storage.normals[i]) < 0;
      break;
    }
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
  } catch (const detail::OrientationCancelled&) {
    throw InputError(options.source + ": the orientation's coarse run was cancelled");
  }
}

}  // namespace pdd
