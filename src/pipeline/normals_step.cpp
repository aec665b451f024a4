// Estimation and orientation of the input's normals before the run.
#include "pipeline/normals_step.h"

#include <pdd/errors.h>
#include <pdd/normals.h>
#include <pdd/sizing.h>
#include <pdd/solvers.h>

#include "common/cancellation.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace pdd::detail {
namespace {

// Design (b) of issue 17. A coarse progressive run of the spectral solver,
// which ignores the normals' signs (Eq. 16), gives f < 0 inside; each normal
// votes +1 when it points towards increasing f, comparing f a short step on
// either side of its sample, -1 otherwise. Coarse (4x the target edge, a few
// seconds), that is right over most of the surface but not across parts
// thinner than its tets; so it only votes, by segments.
std::vector<double> spectral_votes(const PointSet& input, const ReconstructOptions& options) {
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
  std::vector<double> vote(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Vec3& p = input.points[i];
    const Vec3& n = input.normals[i];
    const double outside = domain.interpolate(p + step * n, domain.f());
    const double inside = domain.interpolate(p - step * n, domain.f());
    vote[i] = outside > inside ? 1 : -1;
  }
  return vote;
}

// Flips every segment whose summed vote is negative; returns the number of segments.
std::size_t turn_segments(PointSet& input, const std::vector<int>& segment,
                          const std::vector<double>& vote) {
  std::size_t segments = 0;
  for (std::size_t i = 0; i < input.size(); ++i) {
    segments += segment[i] == static_cast<int>(i);
    if (vote[segment[i]] < 0) input.normals[i] = -input.normals[i];
  }
  return segments;
}

// The segments over which the normals' relative signs are reliable
// (orient_segments) each take the sign of their points' spectral majority.
void orient_by_spectral_vote(PointSet& input, const ReconstructOptions& options,
                             std::size_t& segments) {
  const std::vector<int> segment =
      orient_segments(input.points, input.normals, options.normal_neighbors);
  const std::vector<double> votes = spectral_votes(input, options);
  std::vector<double> vote(input.size(), 0.0);
  for (std::size_t i = 0; i < input.size(); ++i) vote[segment[i]] += votes[i];
  segments = turn_segments(input, segment, vote);
}

// Each segment takes the sign of the sum of its points' visibility votes: the
// side of the surface from which more rays escape is the outside. At most
// about kVisibilitySamples points vote, every stride-th. A one-sided scan is
// open on both sides, so its votes are unclear: when the segments whose mean
// vote is under kConfidentVote hold more than kUnclearShare of the points,
// those take the spectral majority instead.
constexpr std::size_t kVisibilitySamples = 200000;
constexpr double kUnclearShare = 0.25;
void orient_by_visibility_vote(PointSet& input, const ReconstructOptions& options,
                               NormalsReport& report) {
  std::vector<std::size_t> samples;
  const std::size_t stride = 1 + input.size() / kVisibilitySamples;
  for (std::size_t i = 0; i < input.size(); i += stride) samples.push_back(i);
  const std::vector<double> votes =
      visibility_votes(input.points, input.normals, samples);
  std::vector<double> own(input.size(), 0.0);  // for the normals as they were, per point
  for (std::size_t s = 0; s < samples.size(); ++s) own[samples[s]] = stride * votes[s];
  const std::vector<Vec3> before = input.normals;
  const std::vector<int> segment =
      orient_segments(input.points, input.normals, options.normal_neighbors, &own);
  std::vector<double> vote(input.size(), 0.0);
  std::vector<std::size_t> size(input.size(), 0);
  for (std::size_t i = 0; i < input.size(); ++i) {
    ++size[segment[i]];
    vote[segment[i]] += input.normals[i].dot(before[i]) < 0 ? -own[i] : own[i];
  }
  std::size_t unclear = 0;
  for (std::size_t i = 0; i < input.size(); ++i)
    unclear += std::abs(vote[segment[i]]) < kConfidentVote * static_cast<double>(size[segment[i]]);
  if (static_cast<double>(unclear) > kUnclearShare * static_cast<double>(input.size())) {
    const std::vector<double> spectral = spectral_votes(input, options);
    std::vector<double> majority(input.size(), 0.0);
    for (std::size_t i = 0; i < input.size(); ++i) majority[segment[i]] += spectral[i];
    for (std::size_t r = 0; r < input.size(); ++r)
      if (size[r] > 0 && std::abs(vote[r]) < kConfidentVote * static_cast<double>(size[r]))
        vote[r] = majority[r];
    report.unclear = unclear;
  }
  report.segments = turn_segments(input, segment, vote);
}

}  // namespace

const PointSet& prepare_normals(const PointSet& points, const ReconstructOptions& options,
                                PointSet& storage, NormalsReport& report) {
  // Normals that are all zero are none (a file with the columns but no values).
  const auto is_zero = [](const Vec3& n) { return n.squaredNorm() == 0; };
  const bool estimate = !points.has_normals() || options.normals == NormalsMode::kEstimate ||
                        std::all_of(points.normals.begin(), points.normals.end(), is_zero);
  const bool zeros =
      !estimate && std::any_of(points.normals.begin(), points.normals.end(), is_zero);
  if (!estimate && !zeros && options.normals == NormalsMode::kKeep) return points;
  const auto start = std::chrono::steady_clock::now();
  const auto finish = [&]() -> const PointSet& {
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return storage;
  };
  storage.points = points.points;
  storage.normals = points.normals;
  if (zeros)
    report.filled = fill_missing_normals(storage.points, storage.normals,
                                         options.normal_neighbors, options.source);
  if (!estimate && options.normals == NormalsMode::kKeep) return finish();

  // On noisy points (noise near the spacing), normals fitted over k points and
  // steps between raw neighbours are mostly noise: the estimation then fits
  // jets at a scale that follows the noise, and the orientation runs on the
  // points projected onto them.
  report.neighbors = noise_scaled_neighbors(estimate_noise(points), average_spacing(points),
                                            options.normal_neighbors);
  report.smoothed = report.neighbors > options.normal_neighbors;
  // The spectral solver ignores the normals' signs (Eq. 16): estimated normals
  // are not oriented for it unless re-orienting was asked for.
  if (options.solver.kind == SolverKind::kSpectral && options.normals != NormalsMode::kOrient) {
    const JetFits fits = fit_jets(points.points, report.neighbors, options.source);
    storage.normals = sharpen_normals(points.points, fits, report.neighbors, &report.sharpened);
    report.estimated = true;
    return finish();
  }
  // The jets over the input's points, at the noise's scale on noisy points:
  // the estimated normals handed on, and the smoothed points.
  JetFits jets;
  if (estimate || report.smoothed) jets = fit_jets(points.points, report.neighbors, options.source);
  PointSet guide;  // the geometry the orientation runs on
  guide.points = report.smoothed ? std::move(jets.points) : points.points;
  // The guide's own jets span the plain neighbourhood: its points are already
  // smoothed at the noise's scale, and a fit at that scale again would span
  // both sides of parts about as thin as the noise (the bunny's ears).
  guide.normals = report.smoothed
                      ? estimate_normals(guide.points, options.normal_neighbors, options.source)
                  : estimate ? jets.normals
                             : storage.normals;
  const std::vector<Vec3> before = estimate ? guide.normals : storage.normals;
  report.estimated = estimate;
  report.oriented = true;
  report.orientation = options.orientation;
  switch (options.orientation) {
    case Orientation::kMst:
      orient_normals_mst(guide.points, guide.normals, options.normal_neighbors, &report.unreached);
      break;
    case Orientation::kSpectral:
      orient_by_spectral_vote(guide, options, report.segments);
      break;
    case Orientation::kVisibility:
      orient_by_visibility_vote(guide, options, report);
      break;
  }
  // The normals handed on are the jets' over the input's points, sharpened at
  // the features (on noisy points the guide's, fitted over fewer smoothed
  // points, follow the noise's scale less: docs/benchmarks.md, "Normals"), or
  // the given ones; they take the sign of the oriented guide.
  if (estimate)
    storage.normals = sharpen_normals(points.points, jets, report.neighbors, &report.sharpened);
  for (std::size_t i = 0; i < storage.size(); ++i) {
    if (storage.normals[i].dot(guide.normals[i]) < 0) storage.normals[i] = -storage.normals[i];
    report.flipped += (estimate ? guide.normals[i] : storage.normals[i]).dot(before[i]) < 0;
  }
  return finish();
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
