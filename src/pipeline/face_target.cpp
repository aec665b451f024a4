#include "pipeline/face_target.h"

#include <algorithm>
#include <cmath>

namespace pdd::detail {
namespace {

// Output triangles per target-sized isofacet (the sum of area / target over
// the isofacets, which stays about the same as the loop refines): measured
// on the runs of docs/benchmarks.md, "Output size".
constexpr double kTrianglesPerTargetFacet = 1.7;
// The prediction needs enough isofacets to be within about 5 % (1.35x over
// the first 200, 1.05x from 2000 on), but must come before the domain is
// finer than a small target asks for.
constexpr int kMinFacetsToPredict = 200;
constexpr double kTolerance = 0.05;

}  // namespace

bool FaceTarget::fit(std::shared_ptr<const SizingField>& sizing, const IsofacetAreaStats& stats) {
  if (faces_ == 0) return false;
  if (stats.count < std::min<double>(2000, std::max<double>(kMinFacetsToPredict, 0.1 * faces_)))
    return false;
  const double predicted = kTrianglesPerTargetFacet * stats.count * stats.mean_ratio;
  const double factor = predicted / static_cast<double>(faces_);
  if (std::abs(factor - 1) <= kTolerance) return false;
  scaling_ *= factor;
  sizing = scaled_sizing(std::move(sizing), factor);
  return true;
}

}  // namespace pdd::detail
