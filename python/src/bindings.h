// The native part of the Python module: numpy arrays to and from the
// library's types, and the functions that module.cpp exposes.
#pragma once

#include <pdd/types.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

namespace pdd::python {

namespace py = pybind11;

// An (n, 3) array of float64 or float32 (any strides; other real or integer
// dtypes are converted) as n points; ValueError naming `what` otherwise.
std::vector<Vec3> vectors_from_array(const py::handle& array, const std::string& what);

// `points` and, when not None, `normals`: arrays of the same shape (n, 3).
PointSet point_set_from_arrays(const py::handle& points, const py::handle& normals);

// vertices (n, 3) and faces (m, 3) of integers, validated (validate_mesh).
TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces,
                              const std::string& what);

// Attributes as Python passes them: a list of (name, PLY type, (n,) array of numbers).
// ValueError when an entry is not one; validate_points checks the values.
std::vector<Attribute> attributes_from_list(const py::handle& list);
// The same, the values as float64 arrays that own their memory.
py::list list_from(std::vector<Attribute>&& attributes);

// Arrays that own the vectors' memory (no copy): (n, 3) float64 and (m, 3) int32.
py::array array_from(std::vector<Vec3>&& vectors);
py::array array_from(std::vector<std::array<int, 3>>&& faces);

// pdd.reconstruct's native part (reconstruct.cpp).
py::dict reconstruct(const py::handle& points, const py::handle& normals,
                     const py::handle& attributes,
                     const std::vector<std::pair<std::string, std::string>>& options,
                     const py::object& progress, const std::string& domain_out,
                     const std::string& save_iterations);

}  // namespace pdd::python
