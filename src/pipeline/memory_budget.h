// Private to src/pipeline: the domain's vertex budget that a run's memory
// budget allows, and the coarsening of the sizing field that keeps the
// progressive loop within it.
#pragma once

#include <pdd/pipeline.h>
#include <pdd/refine.h>
#include <pdd/sizing.h>

#include <cstddef>
#include <memory>

namespace pdd::detail {

// 3/4 of the memory the machine has available now (MemAvailable of
// /proc/meminfo; the physical memory where that is missing).
std::size_t default_memory_budget();

class VertexBudget {
 public:
  // `bytes` (0: default_memory_budget()) for a run on `num_points` samples;
  // `in_proportion`: the sizing is the default one, so the domain is also kept
  // in proportion to the input (MemoryBudget::input_vertices). InputError when
  // the budget cannot hold the input and a minimal domain.
  VertexBudget(std::size_t bytes, std::size_t num_points, bool in_proportion);

  // The final domain that the current isosurface predicts at `sizing`'s
  // targets (`stats`: its isofacets against them); when it exceeds the
  // budget, `sizing` becomes a coarser copy that fits and true is returned.
  bool fit(std::shared_ptr<const SizingField>& sizing, const IsofacetAreaStats& stats);

  // Whether a domain of this many vertices may still be refined: under 3/4
  // of the vertex budget, since a late refinement pass adds at most half.
  bool allows_refining(std::size_t vertices);

  const MemoryBudget& report() const { return report_; }

 private:
  MemoryBudget report_;
};

}  // namespace pdd::detail
