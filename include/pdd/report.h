// Reports of a reconstruction: the per-iteration statistics as JSON (for
// --stats) and as a text table (printed at the end of a run).
#pragma once

#include <pdd/pipeline.h>

#include <string>

namespace pdd {

// A JSON object: the options that shaped the run, per-iteration statistics
// (vertices, vertices around the isosurface, parsimony, isovertices,
// triangles, solver iterations and residual, seconds per stage, triangle
// quality) and the totals.
std::string statistics_json(const Result& result, const ReconstructOptions& options);

// One line per iteration, aligned columns.
std::string statistics_table(const Result& result);

// One line (no newline) when the memory budget changed the run: the sizing
// coarsened, or refinement stopped at the vertex budget; "" otherwise.
std::string memory_budget_note(const Result& result);

}  // namespace pdd
