// Private to src/pipeline: the output size a run aims at, met by scaling the
// sizing field from what the current isosurface predicts: the size a user
// asks for (ReconstructOptions::target_faces), or, for the adaptive sizing
// with its default tolerance, a share of the uniform default's size (§3.4's
// trade: fewer triangles where the surface is flat, for the same accuracy).
#pragma once

#include <pdd/domain.h>
#include <pdd/refine.h>
#include <pdd/sizing.h>

#include <cstddef>
#include <memory>

namespace pdd::detail {

class FaceTarget {
 public:
  FaceTarget() = default;  // no target
  // `faces` output triangles, with a sizing of kind `adaptive` or not.
  FaceTarget(std::size_t faces, bool adaptive);
  // `share` of the triangles that `reference` (a uniform sizing) would give,
  // with an adaptive sizing.
  FaceTarget(std::shared_ptr<const SizingField> reference, double share);

  // The output triangles that the current isosurface of `domain` predicts at
  // `sizing`'s targets (`stats`: its isofacets against them); when they are
  // off the target by more than a few percent, `sizing` becomes a scaled copy
  // that meets it and true is returned. Does nothing without a target.
  bool fit(const Domain& domain, std::shared_ptr<const SizingField>& sizing,
           const IsofacetAreaStats& stats);

 private:
  std::size_t faces_ = 0;
  double triangles_per_facet_ = 0;
  std::shared_ptr<const SizingField> reference_;
  double share_ = 0;
};

}  // namespace pdd::detail
