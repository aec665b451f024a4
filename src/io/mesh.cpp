// Triangle meshes in and out, dispatched on the file's extension.
#include <limits>
#include <stdexcept>

#include "io/formats.h"
#include "io/text.h"

namespace pdd {

namespace {

const std::vector<io::Format> kMeshFormats = {io::Format::kPly, io::Format::kOff, io::Format::kObj};

}  // namespace

void io::check_face(const std::array<int, 3>& face, std::size_t index, std::size_t num_vertices) {
  for (int v : face) {
    if (v < 0 || static_cast<std::size_t>(v) >= num_vertices) {
      throw std::invalid_argument("face " + std::to_string(index) + " refers to vertex " +
                                  std::to_string(v) + " of a mesh with " +
                                  std::to_string(num_vertices) + " vertices");
    }
  }
}

TriangleMesh read_mesh(const std::string& path) {
  io::format_of(path, kMeshFormats, "mesh");  // before the file is opened
  return io::parse_mesh(path, io::load_file(path));
}

TriangleMesh io::parse_mesh(const std::string& path, const std::string& data) {
  const io::Format format = io::format_of(path, kMeshFormats, "mesh");
  io::RawMesh raw;
  switch (format) {
    case io::Format::kPly:
      raw = io::read_ply(path, data, io::Content::kVerticesAndFaces);
      break;
    case io::Format::kOff:
      raw = io::read_off(path, data, io::Content::kVerticesAndFaces);
      break;
    case io::Format::kObj:
      raw = io::read_obj(path, data, io::Content::kVerticesAndFaces);
      break;
    case io::Format::kXyz:
    case io::Format::kVtu:
    case io::Format::kJson:
      break;  // not mesh formats; format_of has thrown
  }
  const std::vector<Vec3>& points = raw.vertices.points;
  const std::vector<std::size_t>& lines = raw.vertices.lines;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) continue;
    const std::string what =
        "vertex " + std::to_string(i + 1) + " has a coordinate that is not finite";
    if (!lines.empty()) io::fail_at_line(path, lines[i], what);
    io::fail(path, what);
  }
  if (raw.faces.empty()) io::fail(path, "holds no faces");
  const auto n = static_cast<std::int64_t>(points.size());
  if (n > std::numeric_limits<int>::max()) io::fail(path, "has too many vertices for int indices");
  io::check_attributes(path, raw.vertices.attributes, points.size(), lines);
  TriangleMesh mesh;
  mesh.vertices = std::move(raw.vertices.points);
  mesh.attributes = std::move(raw.vertices.attributes);
  mesh.faces.reserve(raw.faces.size());
  for (std::size_t f = 0; f < raw.faces.size(); ++f) {
    std::array<int, 3> face;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = raw.faces[f][k];
      if (v < 0 || v >= n) {
        // Messages count vertices as the format does: from 1 in OBJ, from 0 otherwise.
        const std::int64_t shown = format == io::Format::kObj ? v + 1 : v;
        const std::string what = "face " + std::to_string(f + 1) + " refers to vertex " +
                                 std::to_string(shown) + ", but the file has " + std::to_string(n) +
                                 " vertices";
        if (!raw.face_lines.empty()) io::fail_at_line(path, raw.face_lines[f], what);
        io::fail(path, what);
      }
      face[k] = static_cast<int>(v);
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

void write_mesh(const std::string& path, const TriangleMesh& mesh,
                const MeshWriteOptions& options) {
  const io::Format format = io::format_of(path, kMeshFormats, "mesh");
  for (const Attribute& a : mesh.attributes)
    if (a.values.size() != mesh.vertices.size())
      throw std::invalid_argument("write_mesh: attribute '" + a.name + "' has " +
                                  std::to_string(a.values.size()) + " values for " +
                                  std::to_string(mesh.vertices.size()) + " vertices");
  io::write_output(path, options.staged, [&](std::ostream& out) {
    switch (format) {
      case io::Format::kPly:
        io::write_ply(out, mesh.vertices, {}, mesh.attributes, &mesh.faces, options.ascii);
        break;
      case io::Format::kOff:
        io::write_off(out, mesh.vertices, {}, mesh.attributes, mesh.faces);
        break;
      case io::Format::kObj:
        io::write_obj(out, mesh.vertices, {}, mesh.attributes, mesh.faces);
        break;
      case io::Format::kXyz:
      case io::Format::kVtu:
      case io::Format::kJson:
        break;
    }
  });
}

}  // namespace pdd
