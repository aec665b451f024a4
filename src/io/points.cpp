// Point sets in and out, dispatched on the file's extension.
#include "io/formats.h"
#include "io/text.h"

namespace pdd {

namespace {

const std::vector<io::Format> kPointFormats = {io::Format::kPly, io::Format::kXyz, io::Format::kOff,
                                               io::Format::kObj};

}  // namespace

PointSet read_points(const std::string& path, ValidationReport* report,
                     const ValidationOptions& options) {
  io::format_of(path, kPointFormats, "point set");  // before the file is opened
  return io::parse_points(path, io::load_file(path), report, options);
}

PointSet io::parse_points(const std::string& path, const std::string& data,
                          ValidationReport* report, const ValidationOptions& options) {
  const io::Format format = io::format_of(path, kPointFormats, "point set");
  io::RawVertices raw;
  switch (format) {
    case io::Format::kPly:
      raw = io::read_ply(path, data, io::Content::kVertices).vertices;
      break;
    case io::Format::kXyz:
      raw = io::read_xyz(path, data);
      break;
    case io::Format::kOff:
      raw = io::read_off(path, data, io::Content::kVertices).vertices;
      break;
    case io::Format::kObj:
      raw = io::read_obj(path, data, io::Content::kVertices).vertices;
      break;
    case io::Format::kVtu:
    case io::Format::kJson:
      break;  // not a point format; format_of has thrown
  }
  PointSet points;
  points.points = std::move(raw.points);
  points.normals = std::move(raw.normals);
  points.attributes = std::move(raw.attributes);
  PointSet valid = io::validate_points_at(std::move(points), path, raw.lines, report, options);
  if (report)
    for (const std::string& remark : raw.remarks) report->warnings.push_back(path + ": " + remark);
  return valid;
}

void write_points(const std::string& path, const PointSet& points,
                  const PointWriteOptions& options) {
  const io::Format format = io::format_of(path, kPointFormats, "point set");
  if (points.has_normals() && points.normals.size() != points.size()) {
    throw std::invalid_argument("write_points: " + std::to_string(points.normals.size()) +
                                " normals for " + std::to_string(points.size()) + " points");
  }
  write_atomically(path, [&](std::ostream& out) {
    switch (format) {
      case io::Format::kPly:
        io::write_ply(out, points.points, points.normals, points.attributes, nullptr, options.ascii);
        break;
      case io::Format::kXyz:
        io::write_xyz(out, points.points, points.normals);
        break;
      case io::Format::kOff:
        io::write_off(out, points.points, points.normals, points.attributes, {});
        break;
      case io::Format::kObj:
        io::write_obj(out, points.points, points.normals, points.attributes, {});
        break;
      case io::Format::kVtu:
      case io::Format::kJson:
        break;
    }
  });
}

}  // namespace pdd
