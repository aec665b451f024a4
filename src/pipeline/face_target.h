// Private to src/pipeline: the output size a user asks for
// (ReconstructOptions::target_faces) instead of an edge length, met by scaling
// the sizing field from what the current isosurface predicts.
#pragma once

#include <pdd/refine.h>
#include <pdd/sizing.h>

#include <cstddef>
#include <memory>

namespace pdd::detail {

class FaceTarget {
 public:
  explicit FaceTarget(std::size_t faces) : faces_(faces) {}

  // The output triangles that the current isosurface predicts at `sizing`'s
  // targets (`stats`: its isofacets against them); when they are off the
  // target by more than a few percent, `sizing` becomes a scaled copy that
  // meets it and true is returned. Does nothing when no target is set.
  bool fit(std::shared_ptr<const SizingField>& sizing, const IsofacetAreaStats& stats);

  // The product of the scalings so far (> 1: coarser than the starting sizing).
  double scaling() const { return scaling_; }

 private:
  std::size_t faces_;
  double scaling_ = 1;
};

}  // namespace pdd::detail
