// Sizing fields (§3.4): the target area s of the isofacet in each tet crossed
// by the isosurface. Uniform, curvature-adaptive, or supplied by the user.
#pragma once

#include <pdd/domain.h>
#include <pdd/isofacet.h>
#include <pdd/types.h>

#include <functional>
#include <memory>
#include <vector>

namespace pdd {

class SizingField {
 public:
  virtual ~SizingField() = default;
  // s(f_t) for each isofacet, in the order given.
  virtual std::vector<double> target_areas(const Domain& domain,
                                           const std::vector<Isofacet>& facets) const = 0;
  // The same, and away[i] = 1 where facet i lies away from the data, its
  // target coarsened for want of input nearby (coarser_away_from_data): there
  // the solver invents the surface. By default no facet is away.
  virtual std::vector<double> target_areas_marking_away(const Domain& domain,
                                                       const std::vector<Isofacet>& facets,
                                                       std::vector<char>& away) const;
};

// Area of the equilateral triangle of edge h: sqrt(3)/4 h^2.
double area_for_edge_length(double h);

// Average distance from an input point to its k nearest neighbours (CGAL), over
// every stride-th point past 65536 of them.
double average_spacing(const PointSet& input, int k = 6);

// The default uniform target: triangles whose edge is the input's average
// spacing s, so that the output follows the input's resolution, as long as s
// is at most c = 1 % of the bounding box's diagonal. A sparser input gets
// max(0.7 c, c^2 / s), finer the sparser it is: its samples are too far apart
// to show its thin parts, and a wall 3 target edges thick came out with a
// tunnel (docs/benchmarks.md, "Sparse inputs": 2k points on the fandisk,
// genus 1 for 3 seeds in 10 at c, none at 0.7 c; 2k points on the bunny give
// 10k triangles at their spacing, 37k at c, 77k at 0.7 c).
double default_target_area(const PointSet& input);
double default_target_edge(const PointSet& input);

// The same target area everywhere.
std::unique_ptr<SizingField> uniform_sizing(double target_area);

// The target areas of `inner`, each multiplied by `factor` (> 0).
std::unique_ptr<SizingField> scaled_sizing(std::shared_ptr<const SizingField> inner,
                                           double factor);

// Any callable from a position (the isofacet's centroid) to a target area.
std::unique_ptr<SizingField> user_sizing(std::function<double(const Vec3&)> target_area_at);

// Coarser targets where the isosurface has no input nearby (holes, the
// unseen side of a partial scan): there its shape is invented by the solver,
// and refining it at the data's resolution adds vertices that carry nothing.
// Not in the paper. With d the distance from an isofacet's centroid to the
// nearest input point and b = band_spacings x the input's average spacing,
// the target becomes inner x min(max_factor, max(1, (d / b)^2)): unchanged
// within b of the data, growing with the area of a disc of radius d.
struct DataDistanceOptions {
  double band_spacings = 12;  // b in average input spacings
  double max_factor = 4;     // at most this many times the inner target (2x the edge); 1: off
};

std::unique_ptr<SizingField> coarser_away_from_data(std::shared_ptr<const SizingField> inner,
                                                    const PointSet& input,
                                                    const DataDistanceOptions& options = {});

// Curvature-adaptive sizing of §3.4. Values <= 0 mean "derived from the
// input" as described on each field.
struct AdaptiveSizingOptions {
  int neighbors = 16;        // k: jet-fitting neighbourhood and curvature look-up around an isofacet
  int jet_degree = 2;        // degree of the fitted jet / Monge form
  double gradation = 1.0;    // lambda of the mapping c' = ((c - c_min)/(c_max - c_min))^lambda ...
  double tolerance = 0;      // d, distance tolerance; <= 0: chosen so that s(c_median) equals
                             // default_target_area(input) (a run then scales the field to
                             // 0.8x the uniform default's triangles: pipeline.h)
  double min_area = 0;       // s_min; <= 0: default_target_area(input) / 16
  double max_area = 0;       // s_max; <= 0: default_target_area(input) * 16
};

// Principal curvatures of the input by jet fitting on k nearest neighbours
// (CGAL Monge_via_jet_fitting); returns max(|k1|, |k2|) per point.
std::vector<double> max_abs_curvature(const PointSet& input, int neighbors, int jet_degree);

std::unique_ptr<SizingField> adaptive_sizing(const PointSet& input,
                                             const AdaptiveSizingOptions& options = {});

}  // namespace pdd
