#include "round_trip.h"

#include <pdd/errors.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "io/formats.h"

namespace pdd::fuzz {
namespace {

[[noreturn]] void mismatch(const char* what) {
  std::fprintf(stderr, "fuzz: %s differs once written and read back\n", what);
  std::abort();
}

bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

void expect_same(const std::vector<Attribute>& a, const std::vector<Attribute>& b) {
  if (a.size() != b.size()) mismatch("the number of attributes");
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].name != b[k].name || a[k].type != b[k].type) mismatch("an attribute's name or type");
    if (a[k].values.size() != b[k].values.size()) mismatch("an attribute's length");
    for (std::size_t i = 0; i < a[k].values.size(); ++i)
      if (!same(a[k].values[i], b[k].values[i])) mismatch("an attribute's value");
  }
}

// Whether the format writes `attributes` back as they are: PLY all of them,
// OBJ its 0-1 colours, OFF its 0-255 ones (0-1 ones become 0-255), XYZ none.
bool exact_attributes(const std::string& extension, const std::vector<Attribute>& attributes) {
  if (extension == ".ply" || extension == ".obj") return true;
  return extension == ".off" && (attributes.empty() || attributes[0].type == "uchar");
}

// The file's format under both of its writers' forms (PLY: binary and ASCII).
template <class Write>
void for_each_form(const std::string& extension, Write write) {
  if (extension == ".ply") {
    write(false);
    write(true);
  } else {
    write(false);
  }
}

void points_round_trip(const std::string& name, const std::string& extension,
                       const std::string& data) {
  ValidationReport report;
  PointSet first;
  try {
    first = io::parse_points(name, data, &report, ValidationOptions{});
  } catch (const InputError&) {
    return;  // refused, with a message: what the reader should do with bad bytes
  }
  for_each_form(extension, [&](bool ascii) {
    std::ostringstream out;
    if (extension == ".ply")
      io::write_ply(out, first.points, first.normals, first.attributes, nullptr, ascii);
    else if (extension == ".off")
      io::write_off(out, first.points, first.normals, first.attributes, {});
    else if (extension == ".obj")
      io::write_obj(out, first.points, first.normals, first.attributes, {});
    else
      io::write_xyz(out, first.points, first.normals);
    const PointSet second = io::parse_points(name, out.str(), nullptr, ValidationOptions{});
    if (second.points != first.points) mismatch("a point");
    if (second.normals != first.normals) mismatch("a normal");
    if (exact_attributes(extension, first.attributes))
      expect_same(first.attributes, second.attributes);
  });
}

void mesh_round_trip(const std::string& name, const std::string& extension,
                     const std::string& data) {
  if (extension == ".xyz") return;  // not a mesh format
  TriangleMesh first;
  try {
    first = io::parse_mesh(name, data);
  } catch (const InputError&) {
    return;
  }
  for_each_form(extension, [&](bool ascii) {
    std::ostringstream out;
    if (extension == ".ply")
      io::write_ply(out, first.vertices, {}, first.attributes, &first.faces, ascii);
    else if (extension == ".off")
      io::write_off(out, first.vertices, {}, first.attributes, first.faces);
    else
      io::write_obj(out, first.vertices, {}, first.attributes, first.faces);
    const TriangleMesh second = io::parse_mesh(name, out.str());
    if (second.vertices != first.vertices) mismatch("a vertex");  // finite: read_mesh checks
    if (second.faces != first.faces) mismatch("a face");
    if (exact_attributes(extension, first.attributes))
      expect_same(first.attributes, second.attributes);
  });
}

}  // namespace

int read_write_read(const char* name, const std::uint8_t* data, std::size_t size) {
  const std::string path = name;
  const std::string extension = path.substr(path.rfind('.'));
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  points_round_trip(path, extension, bytes);
  mesh_round_trip(path, extension, bytes);
  return 0;
}

}  // namespace pdd::fuzz
