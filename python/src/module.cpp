// The native module `pdd._pdd`. The package python/pdd wraps it in the
// documented API (pdd.reconstruct, pdd.read_points, ...); errors of the library
// become ValueError (bad input or options) and RuntimeError (a failed solve),
// with the command line's messages.
#include <pdd/compare.h>
#include <pdd/errors.h>
#include <pdd/io.h>
#include <pdd/options.h>
#include <pdd/outliers.h>
#include <pdd/pipeline.h>
#include <pdd/report.h>

#include <pybind11/stl.h>

#include "bindings.h"

namespace py = pybind11;
using namespace pdd;
using namespace pdd::python;

namespace {

const char* kind_name(OptionSpec::Kind kind) {
  switch (kind) {
    case OptionSpec::Kind::kChoice: return "choice";
    case OptionSpec::Kind::kNumber: return "number";
    case OptionSpec::Kind::kInteger: return "integer";
    case OptionSpec::Kind::kSeed: return "seed";
    case OptionSpec::Kind::kSize: return "size";
    case OptionSpec::Kind::kFlag: return "flag";
    case OptionSpec::Kind::kText: return "text";
  }
  return "unknown";
}

py::list option_specs() {
  py::list specs;
  for (const OptionSpec& spec : reconstruct_option_specs()) {
    py::dict d;
    d["name"] = spec.name;
    d["kind"] = kind_name(spec.kind);
    d["help"] = spec.help;
    d["choices"] = spec.choices;
    d["default"] = spec.default_text;
    specs.append(d);
  }
  return specs;
}

py::tuple read_points_arrays(const std::string& path) {
  ValidationReport report;
  PointSet points = read_points(path, &report);
  const bool has_normals = points.has_normals();
  py::object normals = py::none();
  if (has_normals) normals = array_from(std::move(points.normals));
  return py::make_tuple(array_from(std::move(points.points)), normals, report.warnings,
                        list_from(std::move(points.attributes)));
}

py::tuple read_mesh_arrays(const std::string& path) {
  TriangleMesh mesh = read_mesh(path);
  return py::make_tuple(array_from(std::move(mesh.vertices)), array_from(std::move(mesh.faces)),
                        list_from(std::move(mesh.attributes)));
}

void write_mesh_arrays(const std::string& path, const py::handle& vertices,
                       const py::handle& faces, const py::handle& attributes, bool ascii) {
  TriangleMesh mesh = mesh_from_arrays(vertices, faces, "mesh");
  mesh.attributes = attributes_from_list(attributes);
  validate_mesh(mesh, "mesh");
  py::gil_scoped_release release;
  write_mesh(path, mesh, {ascii});
}

std::string quality_json(const py::handle& vertices, const py::handle& faces) {
  const TriangleMesh mesh = mesh_from_arrays(vertices, faces, "mesh");
  py::gil_scoped_release release;
  return quality_report("mesh", mesh, true);
}

std::string compare_json(const py::handle& a_vertices, const py::handle& a_faces,
                         const py::handle& b_vertices, const py::handle& b_faces,
                         std::size_t samples, double fscore_threshold, std::uint64_t seed) {
  const TriangleMesh a = mesh_from_arrays(a_vertices, a_faces, "a");
  const TriangleMesh b = mesh_from_arrays(b_vertices, b_faces, "b");
  require_area(a, "a");
  require_area(b, "b");
  CompareOptions options;
  options.samples = samples;
  options.fscore_threshold = fscore_threshold;
  options.seed = seed;  // compare_surfaces checks the options (std::invalid_argument: ValueError)
  py::gil_scoped_release release;
  return comparison_report("a", "b", options, compare_surfaces(a, b, options), true);
}

// pdd.estimate_normals: the run's first step alone (pipeline.h, prepare_normals).
py::tuple prepare_normals_arrays(const py::handle& points, const py::handle& normals,
                                 const std::vector<std::pair<std::string, std::string>>& options) {
  ReconstructOptions run_options;
  for (const auto& [name, value] : options) set_reconstruct_option(run_options, name, value);
  const PointSet input = validate_points(point_set_from_arrays(points, normals), "points");
  Result result;
  PointSet prepared;
  {
    py::gil_scoped_release release;
    prepared = prepare_normals(input, run_options, &result.normals);
  }
  return py::make_tuple(array_from(std::move(prepared.points)),
                        array_from(std::move(prepared.normals)), normals_note(result),
                        result.normals.flipped);
}

}  // namespace

PYBIND11_MODULE(_pdd, m) {
  m.doc() = "Native part of pdd; use the package `pdd`.";
  m.attr("__version__") = PDD_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const SolverError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<Progress>(m, "Progress",
                       "Where a run is: stage, iteration, domain vertices, seconds since its start.")
      .def_readonly("stage", &Progress::stage,
                    "initialize, solve, optimize, refine or contour")
      .def_readonly("iteration", &Progress::iteration,
                    "1-based; 0 during initialization, the final solve is the last + 1")
      .def_readonly("vertices", &Progress::vertices, "vertices of the current domain")
      .def_readonly("elapsed_seconds", &Progress::elapsed_seconds, "seconds since the start")
      .def("__repr__", [](const Progress& p) {
        return "Progress(stage='" + p.stage + "', iteration=" + std::to_string(p.iteration) +
               ", vertices=" + std::to_string(p.vertices) +
               ", elapsed_seconds=" + std::to_string(p.elapsed_seconds) + ")";
      });

  m.def("option_specs", &option_specs,
        "The options of pdd reconstruct: name, kind, help, choices, default (text; '' = derived).");
  m.def("compare_defaults", [] {
    const CompareOptions d;
    py::dict out;
    out["samples"] = d.samples;
    out["max_samples"] = CompareOptions::kMaxSamples;
    out["fscore_threshold"] = d.fscore_threshold;
    out["seed"] = d.seed;
    return out;
  });
  // The conversions of a point array into the library and of its vectors back,
  // alone: for bench/python_overhead.py.
  m.def("convert_points", [](const py::handle& points) {
    return array_from(vectors_from_array(points, "points"));
  }, py::arg("points"));
  m.def("reconstruct", &pdd::python::reconstruct, py::arg("points"), py::arg("normals"),
        py::arg("attributes"), py::arg("options"),
        py::arg("progress"), py::arg("domain_out"), py::arg("save_iterations"));
  m.def("prepare_normals", &prepare_normals_arrays, py::arg("points"), py::arg("normals"),
        py::arg("options"));
  m.def("read_points", &read_points_arrays, py::arg("path"));
  m.def("read_mesh", &read_mesh_arrays, py::arg("path"));
  m.def("write_mesh", &write_mesh_arrays, py::arg("path"), py::arg("vertices"), py::arg("faces"),
        py::arg("attributes"), py::arg("ascii"));
  m.def("find_outliers", [](const py::handle& points, double ratio, int neighbors) {
    OutlierOptions options;
    options.ratio = ratio;
    options.neighbors = neighbors;
    const std::vector<Vec3> p = vectors_from_array(points, "points");
    std::vector<char> mask;
    {
      py::gil_scoped_release release;
      mask = find_outliers(p, options);
    }
    py::array_t<bool> out(static_cast<py::ssize_t>(mask.size()));
    auto w = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < mask.size(); ++i) w(static_cast<py::ssize_t>(i)) = mask[i] != 0;
    return out;
  }, py::arg("points"), py::arg("ratio"), py::arg("neighbors"));
  m.def("quality", &quality_json, py::arg("vertices"), py::arg("faces"));
  m.def("compare", &compare_json, py::arg("a_vertices"), py::arg("a_faces"),
        py::arg("b_vertices"), py::arg("b_faces"), py::arg("samples"),
        py::arg("fscore_threshold"), py::arg("seed"));
}
