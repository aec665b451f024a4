// Sizing fields of §3.4: uniform, user-supplied and curvature-adaptive.
#include <pdd/errors.h>
#include <pdd/sizing.h>

#include "common/nearest_neighbors.h"
#include "common/statistics_sample.h"

#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "common/cancellation.h"
namespace pdd {

std::vector<double> SizingField::target_areas_marking_away(const Domain& domain,
                                                           const std::vector<Isofacet>& facets,
                                                           std::vector<char>& away) const {
  away.assign(facets.size(), 0);
  return target_areas(domain, facets);
}

namespace {

// A field computed with its marks (SizingField::target_areas_marking_away);
// its plain targets drop them.
class MarkingSizing : public SizingField {
 public:
  std::vector<double> target_areas(const Domain& domain,
                                   const std::vector<Isofacet>& facets) const final {
    std::vector<char> away;
    return target_areas_marking_away(domain, facets, away);
  }
};

class UniformSizing : public SizingField {
 public:
  explicit UniformSizing(double area) : area_(area) {}
  std::vector<double> target_areas(const Domain&, const std::vector<Isofacet>& facets) const override {
    return std::vector<double>(facets.size(), area_);
  }

 private:
  double area_;
};

class UserSizing : public SizingField {
 public:
  explicit UserSizing(std::function<double(const Vec3&)> at) : at_(std::move(at)) {}
  std::vector<double> target_areas(const Domain&, const std::vector<Isofacet>& facets) const override {
    std::vector<double> out;
    out.reserve(facets.size());
    for (const Isofacet& a : facets) {
      const double s = at_(a.centroid);
      if (!(s > 0) || !std::isfinite(s))
        throw InputError("sizing field: the user's target area must be positive and finite, got " +
                         std::to_string(s));
      out.push_back(s);
    }
    return out;
  }

 private:
  std::function<double(const Vec3&)> at_;
};

// The inner target, scaled up with the squared distance to the data.
class DataDistanceSizing : public MarkingSizing {
 public:
  DataDistanceSizing(std::shared_ptr<const SizingField> inner, const PointSet& input,
                     const DataDistanceOptions& options)
      : inner_(std::move(inner)),
        options_(options),
        band_(options.band_spacings * average_spacing(input)),
        points_(input.points),
        neighbors_(points_) {}

  std::vector<double> target_areas_marking_away(const Domain& domain,
                                                const std::vector<Isofacet>& facets,
                                                std::vector<char>& away) const override {
    std::vector<double> s = inner_->target_areas_marking_away(domain, facets, away);
    detail::polled_parallel_for(facets.size(), [&](std::size_t i) {
      const Vec3& c = facets[i].centroid;
      const double d = (points_[neighbors_.query(c, 1).front()] - c).norm() / band_;
      s[i] *= std::clamp(d * d, 1.0, options_.max_factor);
      if (d > 1 && options_.max_factor > 1) away[i] = 1;
    });
    return s;
  }

 private:
  std::shared_ptr<const SizingField> inner_;
  DataDistanceOptions options_;
  double band_;
  std::vector<Vec3> points_;
  detail::NearestNeighbors neighbors_;
};

// Curvature-adaptive sizing, §3.4 "Adaptive Sizing Field".
class AdaptiveSizing : public SizingField {
 public:
  AdaptiveSizing(const PointSet& input, const AdaptiveSizingOptions& options)
      : options_(options),
        curvature_(max_abs_curvature(input, options.neighbors, options.jet_degree)),
        neighbors_(input.points) {
    c_min_ = *std::min_element(curvature_.begin(), curvature_.end());
    c_max_ = *std::max_element(curvature_.begin(), curvature_.end());
    const double base = default_target_area(input);
    if (options_.min_area <= 0) options_.min_area = base / 16;
    if (options_.max_area <= 0) options_.max_area = base * 16;
    if (options_.tolerance <= 0) {
      // s(c) ~ 8 sqrt(3) d / c for small d: pick d so that s(c_median) = base.
      std::vector<double> sorted = curvature_;
      std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
      const double c_median = std::max(sorted[sorted.size() / 2], 1e-12);
      options_.tolerance = base * c_median / (8 * std::sqrt(3.0));
    }
  }

  std::vector<double> target_areas(const Domain& domain,
                                   const std::vector<Isofacet>& facets) const override {
    // Curvature per crossing tet: the mean over the k nearest input points
    // (their maximum spread each curved sample's fine target over a disc of
    // about two spacings: more triangles for the same mean distance).
    std::vector<double> c(facets.size());
    detail::polled_parallel_for(facets.size(), [&](std::size_t i) {
      const auto nearest = neighbors_.query(facets[i].centroid, options_.neighbors);
      double sum = 0;
      for (int j : nearest) sum += curvature_[j];
      c[i] = nearest.empty() ? 0.0 : sum / static_cast<double>(nearest.size());
    });
    // Smoothed like the ASAP volume field (average over the tet and its
    // crossing neighbours), then clipped to [c_min, c_max].
    std::vector<int> facet_of_tet(domain.num_tets(), -1);
    for (std::size_t i = 0; i < facets.size(); ++i) facet_of_tet[facets[i].tet] = static_cast<int>(i);
    std::vector<double> s(facets.size());
    const double d = options_.tolerance;
    for (std::size_t i = 0; i < facets.size(); ++i) {
      double sum = c[i];
      int n = 1;
      for (int nb : domain.tet_neighbors()[facets[i].tet])
        if (nb >= 0 && facet_of_tet[nb] >= 0) {
          sum += c[facet_of_tet[nb]];
          ++n;
        }
      const double smoothed = std::clamp(sum / n, c_min_, c_max_);
      // Gradation mapping c' with exponent lambda.
      const double range = c_max_ - c_min_;
      const double mapped =
          range > 0 ? std::pow((smoothed - c_min_) / range, options_.gradation) * range + c_min_
                    : smoothed;
      // s = 4 sqrt(3) (2d/c - d^2), clipped to [s_min, s_max].
      const double target = mapped > 0 ? 4 * std::sqrt(3.0) * (2 * d / mapped - d * d)
                                       : options_.max_area;
      s[i] = std::clamp(target, options_.min_area, options_.max_area);
    }
    return s;
  }

 private:
  AdaptiveSizingOptions options_;
  std::vector<double> curvature_;
  detail::NearestNeighbors neighbors_;
  double c_min_ = 0, c_max_ = 0;
};

}  // namespace

double area_for_edge_length(double h) { return std::sqrt(3.0) / 4.0 * h * h; }

double average_spacing(const PointSet& input, int k) {
  // CGAL's compute_average_spacing (the mean over the points of the mean
  // distance from each to its k + 1 nearest, itself among them) on CGAL's
  // kd-tree, written out so that the run's cancellation is polled and both
  // cores work, over every stride-th point past 65536 (statistics_sample.h).
  if (input.points.empty() || k < 1) return 0;
  const detail::NearestNeighbors tree(input.points);
  const std::vector<Vec3>& x = input.points;
  const std::size_t stride = detail::statistics_stride(x.size());
  std::vector<double> spacing((x.size() + stride - 1) / stride);
  detail::polled_parallel_for(spacing.size(), [&](std::size_t s) {
    const std::size_t i = s * stride;
    const std::vector<int> near = tree.query(x[i], k + 1);
    double sum = 0;
    for (int j : near) sum += (x[j] - x[i]).norm();
    spacing[s] = sum / static_cast<double>(near.size());
  });
  return std::accumulate(spacing.begin(), spacing.end(), 0.0) / static_cast<double>(spacing.size());
}

double default_target_edge(const PointSet& input) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : input.points) box.extend(p);
  const double spacing = average_spacing(input);
  const double cap = 0.01 * box.diagonal().norm();
  if (spacing <= cap) return spacing;
  // Sparser than the cap: the finer, relative to the spacing, the sparser the input.
  return std::max(0.7 * cap, cap * cap / spacing);
}

double default_target_area(const PointSet& input) {
  return area_for_edge_length(default_target_edge(input));
}

std::unique_ptr<SizingField> uniform_sizing(double target_area) {
  if (!(target_area > 0) || !std::isfinite(target_area))
    throw InputError("sizing field: the target area must be positive and finite, got " +
                     std::to_string(target_area));
  return std::make_unique<UniformSizing>(target_area);
}

namespace {

class ScaledSizing final : public MarkingSizing {
 public:
  ScaledSizing(std::shared_ptr<const SizingField> inner, double factor)
      : inner_(std::move(inner)), factor_(factor) {}
  std::vector<double> target_areas_marking_away(const Domain& domain,
                                                const std::vector<Isofacet>& facets,
                                                std::vector<char>& away) const override {
    std::vector<double> s = inner_->target_areas_marking_away(domain, facets, away);
    for (double& a : s) a *= factor_;
    return s;
  }

 private:
  std::shared_ptr<const SizingField> inner_;
  double factor_;
};

}  // namespace

std::unique_ptr<SizingField> scaled_sizing(std::shared_ptr<const SizingField> inner,
                                           double factor) {
  if (!(factor > 0) || !std::isfinite(factor))
    throw std::invalid_argument("scaled_sizing: the factor must be positive and finite");
  return std::make_unique<ScaledSizing>(std::move(inner), factor);
}

std::unique_ptr<SizingField> coarser_away_from_data(std::shared_ptr<const SizingField> inner,
                                                    const PointSet& input,
                                                    const DataDistanceOptions& options) {
  if (!inner) throw InputError("sizing field: no inner field to coarsen");
  if (input.size() < 2) throw InputError("sizing field: at least two input points are needed");
  if (!(options.band_spacings > 0) || !std::isfinite(options.band_spacings))
    throw InputError("sizing field: the data band must be positive, got " +
                     std::to_string(options.band_spacings));
  if (!(options.max_factor >= 1) || !std::isfinite(options.max_factor))
    throw InputError("sizing field: the coarsening factor must be >= 1, got " +
                     std::to_string(options.max_factor));
  return std::make_unique<DataDistanceSizing>(std::move(inner), input, options);
}

std::unique_ptr<SizingField> user_sizing(std::function<double(const Vec3&)> target_area_at) {
  return std::make_unique<UserSizing>(std::move(target_area_at));
}

std::vector<double> max_abs_curvature(const PointSet& input, int neighbors, int jet_degree) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Fitting = CGAL::Monge_via_jet_fitting<Kernel>;
  const int needed = (jet_degree + 1) * (jet_degree + 2) / 2;
  if (neighbors < needed)
    throw InputError("adaptive sizing: jet fitting of degree " + std::to_string(jet_degree) +
                     " needs at least " + std::to_string(needed) + " neighbours, got " +
                     std::to_string(neighbors));
  if (static_cast<int>(input.size()) < neighbors)
    throw InputError("adaptive sizing: " + std::to_string(neighbors) +
                     " neighbours requested but the input has only " +
                     std::to_string(input.size()) + " points");
  const detail::NearestNeighbors knn(input.points);
  std::vector<double> curvature(input.size());
  detail::polled_parallel_for(input.size(), [&](std::size_t i) {
    std::vector<Kernel::Point_3> local;
    for (int j : knn.query(input.points[i], neighbors))
      local.emplace_back(input.points[j].x(), input.points[j].y(), input.points[j].z());
    Fitting fitting;
    const Fitting::Monge_form monge = fitting(local.begin(), local.end(), jet_degree, 2);
    curvature[i] = std::max(std::abs(monge.principal_curvatures(0)),
                            std::abs(monge.principal_curvatures(1)));
  });
  return curvature;
}

std::unique_ptr<SizingField> adaptive_sizing(const PointSet& input,
                                             const AdaptiveSizingOptions& options) {
  return std::make_unique<AdaptiveSizing>(input, options);
}

}  // namespace pdd
