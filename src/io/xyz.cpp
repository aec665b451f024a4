// XYZ / PWN / XYZN text: one point per line, "x y z" or "x y z nx ny nz", the
// same on every line. Blank lines and text after '#' are skipped. As in
// CGAL's read_XYZ, the first line may hold just the number of points; pdd
// checks it against the points found.
#include "io/formats.h"
#include "io/text.h"

namespace pdd::io {

RawVertices read_xyz(const std::string& path, const std::string& data) {
  LineReader reader(data, '#');
  std::vector<std::string_view> tokens;
  RawVertices v;
  std::int64_t announced = -1;  // the optional point count
  std::size_t announced_line = 0;
  std::size_t first_line = 0;  // the first point's line, which sets the columns
  std::size_t columns = 0;
  while (reader.next(tokens)) {
    const std::size_t line = reader.line();
    std::int64_t count = 0;
    if (tokens.size() == 1 && v.points.empty() && announced < 0 &&
        parse_integer(tokens[0], count) && count >= 0) {
      announced = count;
      announced_line = line;
      continue;
    }
    if (columns == 0) {
      if (tokens.size() != 3 && tokens.size() != 6) {
        fail_at_line(path, line,
                     "expected 3 values (x y z) or 6 (x y z nx ny nz), found " +
                         std::to_string(tokens.size()));
      }
      columns = tokens.size();
      first_line = line;
    } else if (tokens.size() != columns) {
      fail_at_line(path, line,
                   "found " + std::to_string(tokens.size()) + " values, but line " +
                       std::to_string(first_line) + " has " + std::to_string(columns) + " (" +
                       (columns == 3 ? "x y z" : "x y z nx ny nz") + ")");
    }
    v.points.emplace_back(double_at(tokens[0], path, line), double_at(tokens[1], path, line),
                          double_at(tokens[2], path, line));
    if (columns == 6) {
      v.normals.emplace_back(double_at(tokens[3], path, line), double_at(tokens[4], path, line),
                             double_at(tokens[5], path, line));
    }
    v.lines.push_back(line);
  }
  if (announced >= 0 && static_cast<std::size_t>(announced) != v.points.size()) {
    fail_at_line(path, announced_line,
                 "announces " + std::to_string(announced) + " points, but the file has " +
                     std::to_string(v.points.size()));
  }
  return v;
}

void write_xyz(std::ostream& out, const std::vector<Vec3>& points,
               const std::vector<Vec3>& normals) {
  std::string text;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) text += ' ';
      append_double(text, points[i][k]);
    }
    for (int k = 0; k < 3 && !normals.empty(); ++k) {
      text += ' ';
      append_double(text, normals[i][k]);
    }
    text += '\n';
    if (text.size() > (1u << 16)) {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace pdd::io
