// OFF (Geomview's object file format), text only: the keyword OFF with the
// optional prefixes C (vertex colours), N (vertex normals) and ST (texture
// coordinates), the counts "nv nf [ne]", nv vertex lines and nf face lines.
// '#' starts a comment. One vertex or face per line.
#include <cmath>

#include "io/formats.h"
#include "io/text.h"

namespace pdd::io {

namespace {

struct OffHeader {
  bool normals = false;
  bool colours = false;
  bool texture = false;
  std::int64_t vertices = 0;
  std::int64_t faces = 0;
};

// The keyword's prefixes, or false when it is not an OFF keyword pdd reads.
bool parse_keyword(std::string_view keyword, OffHeader& header) {
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return false;
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  if (prefix.substr(0, 2) == "ST") {
    header.texture = true;
    prefix.remove_prefix(2);
  }
  if (!prefix.empty() && prefix[0] == 'C') {
    header.colours = true;
    prefix.remove_prefix(1);
  }
  if (!prefix.empty() && prefix[0] == 'N') {
    header.normals = true;
    prefix.remove_prefix(1);
  }
  return prefix.empty();
}

}  // namespace

RawMesh read_off(const std::string& path, const std::string& data, Content content) {
  LineReader reader(data, '#');
  std::vector<std::string_view> tokens;
  OffHeader header;
  if (!reader.next(tokens) || !parse_keyword(tokens[0], header)) {
    fail(path, "not an OFF file: it should start with OFF, NOFF, COFF or CNOFF");
  }
  if (tokens.size() > 1 && tokens[1] == "BINARY") fail(path, "binary OFF is not supported");
  // The counts follow the keyword, on the same line or on the next.
  tokens.erase(tokens.begin());
  if (tokens.empty() && !reader.next(tokens)) {
    fail(path, "malformed header: the counts 'vertices faces edges' are missing");
  }
  const std::size_t counts_line = reader.line();
  if (tokens.size() < 2 || tokens.size() > 3 || !parse_integer(tokens[0], header.vertices) ||
      !parse_integer(tokens[1], header.faces) || header.vertices < 0 || header.faces < 0) {
    fail_at_line(path, counts_line, "malformed header: expected the counts 'vertices faces edges'");
  }
  // Each vertex and face is a line of at least one byte: a count that the
  // rest of the file cannot hold fails at once.
  const auto left = static_cast<std::uint64_t>(data.size() - reader.offset());
  const auto vertices = static_cast<std::uint64_t>(header.vertices);
  const auto faces = content == Content::kVertices ? 0 : static_cast<std::uint64_t>(header.faces);
  if (vertices > left || faces > left - vertices) {
    fail_at_line(path, counts_line,
                 "file is truncated or its header is wrong: it declares " +
                     std::to_string(header.vertices) + " vertices and " +
                     std::to_string(header.faces) + " faces, one line each, but only " +
                     std::to_string(left) + " bytes follow");
  }

  // x y z [nx ny nz] [colour: 1 to 4 values] [s t]
  const std::size_t base = 3 + (header.normals ? 3 : 0) + (header.texture ? 2 : 0);
  const std::size_t most = base + (header.colours ? 4 : 0);
  const std::size_t least = base + (header.colours ? 1 : 0);
  const std::string expected = std::string(header.normals ? "x y z nx ny nz" : "x y z") +
                               (header.colours ? " and a colour" : "") +
                               (header.texture ? " and s t" : "");

  RawMesh mesh;
  RawVertices& v = mesh.vertices;
  // RGB or RGBA colours, 0-255 integers or 0-1 reals, read when every vertex
  // has the same count of 3 or 4 (a single value is a colour map index).
  std::vector<std::array<double, 4>> colours;
  int channels = -1;
  std::string unread;  // why the colours are not read
  bool integers = true;
  for (std::int64_t i = 0; i < header.vertices; ++i) {
    if (!reader.next(tokens)) {
      fail(path, "file is truncated: it ends after " + std::to_string(i) + " of the " +
                     std::to_string(header.vertices) + " vertices the header declares");
    }
    const std::size_t line = reader.line();
    if (tokens.size() < least || tokens.size() > most) {
      fail_at_line(path, line,
                   "vertex " + std::to_string(i + 1) + " has " + std::to_string(tokens.size()) +
                       " values, expected " + expected);
    }
    v.points.emplace_back(double_at(tokens[0], path, line), double_at(tokens[1], path, line),
                          double_at(tokens[2], path, line));
    if (header.normals) {
      v.normals.emplace_back(double_at(tokens[3], path, line), double_at(tokens[4], path, line),
                             double_at(tokens[5], path, line));
    }
    const std::size_t first = header.normals ? 6 : 3;
    for (std::size_t t = first; t < tokens.size(); ++t) {
      double_at(tokens[t], path, line);  // colours and texture must be numbers too
    }
    if (header.colours) {
      const int count = static_cast<int>(tokens.size() - base);
      if (channels < 0) channels = count;
      if (unread.empty() && (count != channels || count < 3))
        unread = "line " + std::to_string(line) + ": vertex " + std::to_string(i + 1) + " has " +
                 std::to_string(count) + " colour value" + (count == 1 ? "" : "s") +
                 (count == channels ? "" : ", the first vertex " + std::to_string(channels));
      std::array<double, 4> row{};
      for (int c = 0; c < count; ++c) {
        const std::string_view token = tokens[first + static_cast<std::size_t>(c)];
        row[static_cast<std::size_t>(c)] = double_at(token, path, line);
        integers = integers && token.find_first_of(".eE") == std::string_view::npos;
      }
      colours.push_back(row);
    }
    v.lines.push_back(line);
  }
  if (!unread.empty())
    v.remarks.push_back("the vertex colours are not read (" + unread +
                        "; pdd reads RGB or RGBA, the same on every vertex)");
  else if (channels >= 3)
    v.attributes = colour_attributes(colours, channels, integers);
  if (content == Content::kVertices) return mesh;

  for (std::int64_t i = 0; i < header.faces; ++i) {
    if (!reader.next(tokens)) {
      fail(path, "file is truncated: it ends after " + std::to_string(i) + " of the " +
                     std::to_string(header.faces) + " faces the header declares");
    }
    const std::size_t line = reader.line();
    const std::string face = "face " + std::to_string(i + 1);
    const std::int64_t n = integer_at(tokens[0], path, line);
    if (n != 3) {
      fail_at_line(
          path, line,
          face + " has " + std::to_string(n) + " vertices; only triangle meshes are supported");
    }
    if (tokens.size() < 4 || tokens.size() > 8) {
      fail_at_line(path, line,
                   face + " has " + std::to_string(tokens.size() - 1) +
                       " values after its vertex count, expected 3 vertex indices "
                       "and an optional colour");
    }
    mesh.faces.push_back({integer_at(tokens[1], path, line), integer_at(tokens[2], path, line),
                          integer_at(tokens[3], path, line)});
    for (std::size_t t = 4; t < tokens.size(); ++t) double_at(tokens[t], path, line);
    mesh.face_lines.push_back(line);
  }
  if (reader.next(tokens)) {
    fail_at_line(path, reader.line(), "data after the last face the header declares");
  }
  return mesh;
}

void write_off(std::ostream& out, const std::vector<Vec3>& vertices,
               const std::vector<Vec3>& normals, const std::vector<Attribute>& attributes,
               const Faces& faces) {
  const std::vector<const Attribute*> colours = colour_channels(attributes);
  std::string text = std::string(colours.empty() ? "" : "C") + (normals.empty() ? "" : "N") + "OFF\n";
  text += std::to_string(vertices.size()) + ' ' + std::to_string(faces.size()) + " 0\n";
  auto flush = [&](bool force) {
    if (force || text.size() > (1u << 16)) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  };
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) text += ' ';
      append_double(text, vertices[i][k]);
    }
    for (int k = 0; k < 3 && !normals.empty(); ++k) {
      text += ' ';
      append_double(text, normals[i][k]);
    }
    // Colours as 0-255 integers, RGB or RGBA as the input had them.
    for (const Attribute* channel : colours) {
      const double unit = unit_colour(*channel, channel->values[i]);
      text += ' ' + std::to_string(static_cast<int>(std::lround(unit * 255)));
    }
    text += '\n';
    flush(false);
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    check_face(faces[i], i, vertices.size());
    text += "3 " + std::to_string(faces[i][0]) + ' ' + std::to_string(faces[i][1]) + ' ' +
            std::to_string(faces[i][2]) + '\n';
    flush(false);
  }
  flush(true);
}

}  // namespace pdd::io
