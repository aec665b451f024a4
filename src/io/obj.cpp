// Wavefront OBJ, the geometry only: "v x y z [w | r g b]", "vn x y z" and
// triangular "f" lines with v, v/vt, v//vn or v/vt/vn corners (1-based;
// negative indices count back from the latest vertex). Every other statement
// (vt, g, o, s, usemtl, mtllib, l, p, ...) is skipped. '#' starts a comment.
#include "io/formats.h"
#include "io/text.h"

namespace pdd::io {

namespace {

// The 0-based vertex index of a face corner "v[/vt[/vn]]".
std::int64_t corner_vertex(std::string_view corner, std::size_t vertices_so_far,
                           const std::string& path, std::size_t line) {
  const std::string_view v = corner.substr(0, corner.find('/'));
  std::int64_t index = 0;
  if (!parse_integer(v, index) || index == 0) {
    fail_at_line(path, line,
                 quote(corner) +
                     " is not a face corner (v, v/vt, "
                     "v//vn or v/vt/vn with v a non-zero vertex number)");
  }
  if (index > 0) return index - 1;
  const std::int64_t absolute = static_cast<std::int64_t>(vertices_so_far) + index;
  if (absolute < 0) {
    fail_at_line(path, line, "vertex " + std::to_string(index) + " is before the first vertex");
  }
  return absolute;
}

}  // namespace

RawMesh read_obj(const std::string& path, const std::string& data, Content content) {
  LineReader reader(data, '#');
  std::vector<std::string_view> tokens;
  RawMesh mesh;
  RawVertices& v = mesh.vertices;
  std::vector<Vec3> normals;
  std::vector<std::array<double, 4>> colours;  // "v x y z r g b": 0-1 reals
  while (reader.next(tokens)) {
    const std::size_t line = reader.line();
    const std::string_view key = tokens[0];
    const std::size_t n = tokens.size() - 1;
    if (key == "v") {
      if (n != 3 && n != 4 && n != 6) {
        fail_at_line(path, line,
                     "'v' has " + std::to_string(n) +
                         " values, expected x y z (optionally followed by w, or "
                         "by a colour r g b)");
      }
      v.points.emplace_back(double_at(tokens[1], path, line), double_at(tokens[2], path, line),
                            double_at(tokens[3], path, line));
      std::array<double, 4> colour{};
      for (std::size_t t = 4; t <= n; ++t) {
        const double value = double_at(tokens[t], path, line);
        if (n == 4 && value != 1.0) {
          fail_at_line(path, line,
                       "the weight w = " + quote(tokens[4]) + " is not supported (only 1)");
        }
        if (n == 6) colour[t - 4] = value;
      }
      if (n == 6) colours.push_back(colour);
      v.lines.push_back(line);
    } else if (key == "vn") {
      if (n != 3) {
        fail_at_line(path, line, "'vn' has " + std::to_string(n) + " values, expected nx ny nz");
      }
      normals.emplace_back(double_at(tokens[1], path, line), double_at(tokens[2], path, line),
                           double_at(tokens[3], path, line));
    } else if (key == "f" && content == Content::kVerticesAndFaces) {
      if (n != 3) {
        fail_at_line(path, line,
                     "face " + std::to_string(mesh.faces.size() + 1) + " has " + std::to_string(n) +
                         " vertices; only triangle meshes are supported");
      }
      mesh.faces.push_back({corner_vertex(tokens[1], v.points.size(), path, line),
                            corner_vertex(tokens[2], v.points.size(), path, line),
                            corner_vertex(tokens[3], v.points.size(), path, line)});
      mesh.face_lines.push_back(line);
    }
  }
  // Colours on every vertex, or none read.
  if (!colours.empty() && colours.size() != v.points.size()) {
    v.remarks.push_back("the vertex colours (v x y z r g b) are not read: " +
                        std::to_string(colours.size()) + " of the " +
                        std::to_string(v.points.size()) + " vertices have one");
  } else if (!colours.empty()) {
    v.attributes = colour_attributes(colours, 3, false);
  }
  if (content == Content::kVertices && !normals.empty()) {
    // OBJ ties normals to face corners, not to vertices; a point set can use
    // them only when there is one per vertex, in the same order.
    if (normals.size() != v.points.size()) {
      fail(path, std::to_string(normals.size()) + " normals (vn) for " +
                     std::to_string(v.points.size()) +
                     " vertices (v); a point set needs one normal per vertex, in order");
    }
    v.normals = std::move(normals);
  }
  return mesh;
}

void write_obj(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces& faces) {
  const std::vector<const Attribute*> colours = colour_channels(attributes);
  std::string text = "# written by pdd " PDD_VERSION "\n";
  auto flush = [&](bool force) {
    if (force || text.size() > (1u << 16)) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  };
  auto put = [&](const char* key, const Vec3& p) {
    text += key;
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_double(text, p[k]);
    }
    text += '\n';
    flush(false);
  };
  // Colours as the widespread "v x y z r g b" extension (0-1; OBJ has no alpha).
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (colours.empty()) {
      put("v", vertices[i]);
      continue;
    }
    text += 'v';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_double(text, vertices[i][k]);
    }
    for (int c = 0; c < 3; ++c) {
      text += ' ';
      append_double(text, unit_colour(*colours[c], colours[c]->values[i]));
    }
    text += '\n';
    flush(false);
  }
  for (const Vec3& n : normals) put("vn", n);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    check_face(faces[i], i, vertices.size());
    text += "f " + std::to_string(faces[i][0] + 1) + ' ' + std::to_string(faces[i][1] + 1) + ' ' +
            std::to_string(faces[i][2] + 1) + '\n';
    flush(false);
  }
  flush(true);
}

}  // namespace pdd::io
