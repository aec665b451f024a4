// pdd.reconstruct: the library's reconstruct() on numpy arrays, with the GIL
// released while it runs and the progress callback as its only way back into
// Python (the user's callback, and Ctrl-C, which cancels the run).
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/options.h>
#include <pdd/pipeline.h>
#include <pdd/report.h>

#include <malloc.h>

#include <exception>

#include "bindings.h"

namespace pdd::python {

py::dict reconstruct(const py::handle& points, const py::handle& normals,
                     const py::handle& attributes,
                     const std::vector<std::pair<std::string, std::string>>& options,
                     const py::object& progress, const std::string& domain_out,
                     const std::string& save_iterations) {
  ReconstructOptions run_options;
  for (const auto& [name, value] : options) set_reconstruct_option(run_options, name, value);
  if (!domain_out.empty()) check_output_path(domain_out, OutputKind::kDomain);
  if (!save_iterations.empty()) check_output_path(save_iterations, OutputKind::kFolder);

  ValidationReport report;
  PointSet given = point_set_from_arrays(points, normals);
  given.attributes = attributes_from_list(attributes);
  const PointSet input = validate_points(std::move(given), "points", &report);
  // The iteration files and the domain appear together, only when the run succeeds.
  StagedOutputs outputs;
  if (!save_iterations.empty())
    run_options.on_iteration = iteration_files(save_iterations, false, &outputs);

  // Called between stages on the calling thread: takes the GIL, lets Python
  // handle pending signals (Ctrl-C raises KeyboardInterrupt there), then asks
  // the user's callback. Either one stops the run; its exception is raised
  // once the run has unwound.
  std::exception_ptr raised;
  run_options.progress = [&](const Progress& p) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (progress.is_none()) return true;
      const py::object answer = progress(p);
      return answer.is_none() || py::bool_(answer);
    } catch (...) {
      raised = std::current_exception();
      return false;
    }
  };

  Result result;
  {
    py::gil_scoped_release release;
    // As the command line does (apps/main.cpp): freed blocks stay in the heap for the next
    // iteration instead of going back to the kernel as fresh zeroed pages; glibc's
    // defaults come back, and the heap is trimmed, once the run is over.
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    struct RestoreMalloc {
      ~RestoreMalloc() {
        mallopt(M_MMAP_THRESHOLD, 128 * 1024);
        mallopt(M_TRIM_THRESHOLD, 128 * 1024);
        malloc_trim(0);
      }
    } restore;
    result = pdd::reconstruct(input, run_options);
  }
  if (raised) std::rethrow_exception(raised);
  py::dict out;
  py::list warnings;
  for (const std::string& w : report.warnings) warnings.append(w);
  out["warnings"] = warnings;
  out["cancelled"] = result.cancelled;
  if (result.cancelled) return out;
  if (result.mesh.faces.empty())
    throw SolverError("points: the isosurface is empty (the solver found no surface)");
  {
    py::gil_scoped_release release;
    if (!domain_out.empty())
      write_domain_vtu(domain_out, result.domain.mesh(), result.domain.f(), {}, {}, &outputs);
    outputs.commit();
  }
  out["stats"] = statistics_json(result, run_options);
  out["table"] = statistics_table(result);
  py::list notes;
  for (const std::string& note : run_notes(result)) notes.append(note);
  out["notes"] = notes;
  out["attributes"] = list_from(std::move(result.mesh.attributes));
  out["vertices"] = array_from(std::move(result.mesh.vertices));
  out["faces"] = array_from(std::move(result.mesh.faces));
  return out;
}

}  // namespace pdd::python
