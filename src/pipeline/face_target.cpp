#include "pipeline/face_target.h"

#include <algorithm>
#include <cmath>

namespace pdd::detail {
namespace {

// Output triangles per target-sized isofacet (the sum of area / target over
// the isofacets, which stays about the same as the loop refines), uniform and
// adaptive: fitted on the shared data, docs/benchmarks.md, "Output size".
constexpr double kTrianglesPerFacetUniform = 1.7;
constexpr double kTrianglesPerFacetAdaptive = 1.8;
// The prediction needs enough isofacets to be within about 5 % (1.35x over
// the first 200, 1.05x from 2000 on), but must come before the domain is
// finer than a small target asks for.
constexpr int kMinFacetsToPredict = 200;
constexpr double kTolerance = 0.05;

}  // namespace

FaceTarget::FaceTarget(std::size_t faces, bool adaptive)
    : faces_(faces),
      triangles_per_facet_(adaptive ? kTrianglesPerFacetAdaptive : kTrianglesPerFacetUniform) {}

FaceTarget::FaceTarget(std::shared_ptr<const SizingField> reference, double share)
    : triangles_per_facet_(kTrianglesPerFacetAdaptive), reference_(std::move(reference)),
      share_(share) {}

bool FaceTarget::fit(const Domain& domain, std::shared_ptr<const SizingField>& sizing,
                     const IsofacetAreaStats& stats) {
  double faces = static_cast<double>(faces_);
  if (reference_) {
    const IsofacetAreaStats uniform = isofacet_area_stats(domain, *reference_);
    faces = share_ * kTrianglesPerFacetUniform * uniform.count * uniform.mean_ratio;
  }
  if (!(faces > 0)) return false;
  if (stats.count < std::min(2000.0, std::max<double>(kMinFacetsToPredict, 0.1 * faces)))
    return false;
  const double predicted = triangles_per_facet_ * stats.count * stats.mean_ratio;
  const double factor = predicted / faces;
  if (std::abs(factor - 1) <= kTolerance) return false;
  sizing = scaled_sizing(std::move(sizing), factor);
  return true;
}

}  // namespace pdd::detail
