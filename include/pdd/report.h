// Reports, shared by the command line and the Python module: a
// reconstruction's per-iteration statistics as JSON (for --stats) and as a
// text table (printed at the end of a run), and the reports of `pdd quality`
// and `pdd compare` as text or JSON.
#pragma once

#include <pdd/compare.h>
#include <pdd/pipeline.h>
#include <pdd/quality.h>

#include <string>
#include <vector>

namespace pdd {

class StagedOutputs;  // io.h

// A JSON object: the options that shaped the run, per-iteration statistics
// (vertices, vertices around the isosurface, parsimony, isovertices,
// triangles, solver iterations and residual, seconds per stage, triangle
// quality) and the totals.
std::string statistics_json(const Result& result, const ReconstructOptions& options);

// One line per iteration, aligned columns.
std::string statistics_table(const Result& result);

// One line (no newline) when the run estimated or oriented the normals: how,
// and how many it flipped; "" otherwise.
std::string normals_note(const Result& result);

// One line (no newline) when the memory budget changed the run: the sizing
// coarsened, or refinement stopped at the vertex budget; "" otherwise.
std::string memory_budget_note(const Result& result);

// One line on the outliers the run dropped, or "" when none.
std::string outliers_note(const Result& result);

// One line on what --trim cut, or "" when the run did not trim.
std::string trim_note(const Result& result);

// One line when an untrimmed output is open (its surface reaches the domain's
// boundary), or "" when it is closed.
std::string open_surface_note(const Result& result);

// The notes above that a run has, in the order the command line prints them
// (the Python module warns with the same).
std::vector<std::string> run_notes(const Result& result);

// --save-iterations: writes the isosurface (.ply) and the domain with f (.vtu)
// of every iteration into `folder`, created if missing (Figure 7). InputError
// at once when `folder` cannot be (check_output_path, OutputKind::kFolder).
// With `staged`, the files (and the folder, when created) appear only when
// staged->commit() does, with the run's other outputs.
IterationCallback iteration_files(const std::string& folder, bool ascii,
                                  StagedOutputs* staged = nullptr);

// `pdd quality MESH [--json]`: triangle quality (angles, histogram) and the
// surface's checks (manifold, closed, components, genus); `file` names it.
std::string quality_report(const std::string& file, const TriangleMesh& mesh, bool as_json);

// `pdd compare A B [--json]`: the distances of compare_surfaces, B the reference.
std::string comparison_report(const std::string& a, const std::string& b,
                              const CompareOptions& options, const SurfaceDistance& distance,
                              bool as_json);

}  // namespace pdd
