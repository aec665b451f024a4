// numpy arrays to and from the library's types. Inputs are read through
// their strides (float64 and float32 without a converted copy); outputs hand
// the library's vectors to numpy without copying them.
#include <pdd/errors.h>
#include <pdd/io.h>

#include <limits>

#include "bindings.h"

namespace pdd::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The array of `object` when numpy can make one; ValueError naming `what` otherwise.
py::array as_array(const py::handle& object, const std::string& what) {
  py::array a = py::reinterpret_borrow<py::object>(object).is_none()
                    ? py::array()
                    : py::array::ensure(object);
  if (!a || a.dtype().kind() == 'O')
    throw InputError(what + ": expected a numpy array of numbers (or a sequence numpy can "
                            "convert), got " + std::string(py::str(py::type::of(object).attr("__name__"))));
  return a;
}

void require_shape(const py::array& a, const std::string& what, const std::string& columns) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(what + ": expected an array of shape (" + columns + ", 3), got shape " +
                     shape_text(a));
}

template <typename T>
std::vector<Vec3> read_rows(const py::array& a) {
  const auto r = a.unchecked<T, 2>();
  std::vector<Vec3> out(static_cast<std::size_t>(r.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) out[i] = Vec3(r(i, 0), r(i, 1), r(i, 2));
  return out;
}

}  // namespace

std::vector<Vec3> vectors_from_array(const py::handle& array, const std::string& what) {
  const py::array a = as_array(array, what);
  require_shape(a, what, "n");
  const char kind = a.dtype().kind();
  if (py::isinstance<py::array_t<double>>(a)) return read_rows<double>(a);
  if (py::isinstance<py::array_t<float>>(a)) return read_rows<float>(a);
  if (kind == 'f' || kind == 'i' || kind == 'u')
    return read_rows<double>(py::array_t<double, py::array::forcecast>::ensure(a));
  throw InputError(what + ": expected real numbers, got an array of dtype " +
                   std::string(py::str(a.dtype())));
}

PointSet point_set_from_arrays(const py::handle& points, const py::handle& normals) {
  PointSet set;
  set.points = vectors_from_array(points, "points");
  if (!py::reinterpret_borrow<py::object>(normals).is_none()) {
    set.normals = vectors_from_array(normals, "normals");
    if (set.normals.size() != set.points.size())
      throw InputError("normals: " + std::to_string(set.normals.size()) + " normals for " +
                       std::to_string(set.points.size()) + " points");
  }
  return set;
}

TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces,
                              const std::string& what) {
  TriangleMesh mesh;
  mesh.vertices = vectors_from_array(vertices, what + ".vertices");
  const py::array f = as_array(faces, what + ".faces");
  require_shape(f, what + ".faces", "m");
  const char kind = f.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InputError(what + ".faces: expected integers, got an array of dtype " +
                     std::string(py::str(f.dtype())));
  const auto indices = py::array_t<long long, py::array::forcecast>::ensure(f);
  const auto r = indices.unchecked<2>();
  mesh.faces.resize(static_cast<std::size_t>(r.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (int k = 0; k < 3; ++k) {
      const long long v = r(i, k);
      // Out of int's range is out of any mesh's range: validate_mesh says so.
      mesh.faces[i][k] = v < 0 || v > std::numeric_limits<int>::max() ? -1 : static_cast<int>(v);
      if (mesh.faces[i][k] < 0)
        throw InputError(what + ": face " + std::to_string(i + 1) + " refers to vertex " +
                         std::to_string(v) + ", but the mesh has " +
                         std::to_string(mesh.vertices.size()) + " vertices");
    }
  validate_mesh(mesh, what);
  return mesh;
}

std::vector<Attribute> attributes_from_list(const py::handle& list) {
  std::vector<Attribute> out;
  if (py::reinterpret_borrow<py::object>(list).is_none()) return out;
  for (const py::handle entry : list) {
    const auto t = py::reinterpret_borrow<py::tuple>(entry);
    Attribute a;
    a.name = t[0].cast<std::string>();
    a.type = t[1].cast<std::string>();
    const py::array values = as_array(t[2], a.name);
    if (values.ndim() != 1)
      throw InputError(a.name + ": expected an array of shape (n,), got shape " +
                       shape_text(values));
    const auto converted = py::array_t<double, py::array::forcecast>::ensure(values);
    const auto r = converted.unchecked<1>();
    a.values.resize(static_cast<std::size_t>(r.shape(0)));
    for (py::ssize_t i = 0; i < r.shape(0); ++i) a.values[i] = r(i);
    out.push_back(std::move(a));
  }
  return out;
}

py::list list_from(std::vector<Attribute>&& attributes) {
  py::list out;
  for (Attribute& a : attributes) {
    auto* owned = new std::vector<double>(std::move(a.values));
    const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    out.append(py::make_tuple(a.name, a.type,
                              py::array_t<double>({static_cast<py::ssize_t>(owned->size())},
                                                  owned->data(), owner)));
  }
  return out;
}

py::array array_from(std::vector<Vec3>&& vectors) {
  auto* owned = new std::vector<Vec3>(std::move(vectors));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<Vec3>*>(p); });
  const auto n = static_cast<py::ssize_t>(owned->size());
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
  return py::array_t<double>({n, py::ssize_t{3}},
                             {static_cast<py::ssize_t>(sizeof(Vec3)),
                              static_cast<py::ssize_t>(sizeof(double))},
                             n ? owned->front().data() : nullptr, owner);
}

py::array array_from(std::vector<std::array<int, 3>>&& faces) {
  using Faces = std::vector<std::array<int, 3>>;
  auto* owned = new Faces(std::move(faces));
  const py::capsule owner(owned, [](void* p) { delete static_cast<Faces*>(p); });
  const auto m = static_cast<py::ssize_t>(owned->size());
  static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int), "faces are three packed ints");
  return py::array_t<int>({m, py::ssize_t{3}},
                          {static_cast<py::ssize_t>(sizeof(std::array<int, 3>)),
                           static_cast<py::ssize_t>(sizeof(int))},
                          m ? owned->front().data() : nullptr, owner);
}

}  // namespace pdd::python
