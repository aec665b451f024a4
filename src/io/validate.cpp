// Validation of an input point set X (§3.1): finite coordinates, usable
// normals, exact duplicates merged, and enough spread for a volume to be
// enclosed (at least 4 points not all in one plane).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/formats.h"
#include "io/text.h"

namespace pdd {

namespace {

std::string short_number(double value) {
  std::ostringstream s;
  s.precision(3);
  s << value;
  return s.str();
}

std::string vector_text(const Vec3& v) {
  return "(" + io::format_double(v.x()) + ", " + io::format_double(v.y()) + ", " +
         io::format_double(v.z()) + ")";
}

bool is_finite(const Vec3& v) { return v.allFinite(); }

struct Box {
  Vec3 lo, hi;
  double diagonal;  // without overflow while it fits in a double
};

Box bounding_box(const std::vector<Vec3>& points) {
  Box box{points[0], points[0], 0};
  for (const Vec3& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  box.diagonal = (box.hi - box.lo).stableNorm();
  return box;
}

// What keeps `points` (at least one, finite, distinct) from bounding a volume
// that pdd can compute with, phrased to follow "all <n> points ", or "". The
// extent is judged on the points' own bounding box and principal axes, not
// on their distance to the origin: a georeferenced scan sits millions of
// units from it.
std::string spread_problem(const std::vector<Vec3>& points, const ValidationOptions& options) {
  const Box box = bounding_box(points);
  const double diagonal = box.diagonal;
  const double magnitude = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  if (!(diagonal <= options.max_extent)) {
    return "span " + (std::isfinite(diagonal) ? short_number(diagonal) : "more than a double holds") +
           " (their bounding-box diagonal), more than the " + short_number(options.max_extent) +
           " pdd computes with; rescale them";
  }
  if (diagonal <= options.coincidence_tolerance * magnitude) {
    return "coincide: their bounding box diagonal, " + short_number(diagonal) +
           ", is within a relative " + short_number(options.coincidence_tolerance) +
           " of their coordinates (" + short_number(magnitude) +
           "), about the rounding of the coordinates";
  }
  if (diagonal < options.min_extent) {
    return "span only " + short_number(diagonal) + " (their bounding-box diagonal), less than the " +
           short_number(options.min_extent) + " pdd computes with; rescale them";
  }
  // The thinnest extents, along the principal axes of the points: an upper
  // bound of the true thinnest extents, so a set rejected here is truly flat.
  // Coordinates relative to the box's centre keep the sums exact enough.
  const Vec3 box_centre = box.lo + 0.5 * (box.hi - box.lo);
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p - box_centre;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) {
    const Vec3 q = p - box_centre - mean;
    covariance += q * q.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  auto extent = [&](int axis) {  // eigenvalues ascend
    const Vec3 direction = eigen.eigenvectors().col(axis);
    double a = INFINITY;
    double b = -INFINITY;
    for (const Vec3& p : points) {
      const double t = (p - box_centre - mean).dot(direction);
      a = std::min(a, t);
      b = std::max(b, t);
    }
    return b - a;
  };
  const double tolerance = options.flatness_tolerance;
  const double thickness = extent(0);
  if (thickness > tolerance * diagonal) return "";
  const bool on_a_line = extent(1) <= tolerance * diagonal;
  return std::string("lie ") + (on_a_line ? "on one line" : "in one plane") + " (thickness " +
         short_number(thickness) + " for a bounding box diagonal of " + short_number(diagonal) +
         "; relative tolerance " + short_number(tolerance) + "); they cannot bound a volume";
}

// The points far from the others: more than kOutlierRatio times farther from
// the points' coordinate-wise median than the median point is; the farthest
// first.
std::vector<std::size_t> outliers(const std::vector<Vec3>& points) {
  constexpr double kOutlierRatio = 1e3;
  const std::size_t n = points.size();
  std::vector<double> values(n);
  auto median = [&] {
    std::nth_element(values.begin(), values.begin() + n / 2, values.end());
    return values[n / 2];
  };
  Vec3 centre;
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < n; ++i) values[i] = points[i][k];
    centre[k] = median();
  }
  std::vector<double> distance(n);
  for (std::size_t i = 0; i < n; ++i) distance[i] = (points[i] - centre).stableNorm();
  values = distance;
  const double typical = median();
  std::vector<std::size_t> far;
  for (std::size_t i = 0; i < n; ++i)
    if (distance[i] > kOutlierRatio * typical) far.push_back(i);
  std::stable_sort(far.begin(), far.end(),
                   [&](std::size_t a, std::size_t b) { return distance[a] > distance[b]; });
  return far;
}

// Merges exact duplicates in place (the first occurrence stays, with its
// normal); the report counts them. Sorting copies of the positions (rather
// than indices into them) keeps the sort cache-friendly on large inputs.
void merge_duplicates(PointSet& points, std::vector<std::size_t>& lines, ValidationReport& report) {
  struct Entry {
    Vec3 p;
    std::size_t index;
  };
  const std::size_t n = points.size();
  std::vector<Entry> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = {points.points[i], i};
  std::sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
    if (a.p.x() != b.p.x()) return a.p.x() < b.p.x();
    if (a.p.y() != b.p.y()) return a.p.y() < b.p.y();
    if (a.p.z() != b.p.z()) return a.p.z() < b.p.z();
    return a.index < b.index;
  });
  std::vector<char> keep(n, 1);
  std::size_t first = 0;  // the first occurrence of the current position in `sorted`
  for (std::size_t i = 1; i < n; ++i) {
    if (sorted[i].p != sorted[first].p) {
      first = i;
      continue;
    }
    const std::size_t kept = sorted[first].index;
    const std::size_t dropped = sorted[i].index;
    keep[dropped] = 0;
    ++report.merged_duplicates;
    if (points.has_normals() && points.normals[kept] != points.normals[dropped]) {
      ++report.merged_with_other_normal;
    }
  }
  if (report.merged_duplicates == 0) return;
  if (!lines.empty()) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (keep[i]) lines[out++] = lines[i];
    lines.resize(out);
  }
  points.keep(keep);
}

}  // namespace

PointSet validate_points(PointSet points, const std::string& source, ValidationReport* report,
                         const ValidationOptions& options) {
  return io::validate_points_at(std::move(points), source, {}, report, options);
}

PointSet io::validate_points_at(PointSet points, const std::string& source,
                                const std::vector<std::size_t>& point_lines,
                                ValidationReport* report, const ValidationOptions& options) {
  ValidationReport local;
  ValidationReport& r = report ? *report : local;
  r = ValidationReport{};
  r.points_read = points.size();
  std::vector<std::size_t> lines = point_lines;
  auto where = [&](std::size_t i) {
    const std::string point = "point " + std::to_string(i + 1);
    return lines.empty() ? point : "line " + std::to_string(lines[i]) + " (" + point + ")";
  };

  if (points.has_normals() && points.normals.size() != points.size()) {
    fail(source, std::to_string(points.normals.size()) + " normals for " +
                     std::to_string(points.size()) + " points");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points.points[i])) {
      fail(source, where(i) + ": the position " + vector_text(points.points[i]) + " is not finite");
    }
    if (!points.has_normals()) continue;
    const Vec3& normal = points.normals[i];
    if (!is_finite(normal)) {
      fail(source, where(i) + ": the normal " + vector_text(normal) + " is not finite");
    }
    if (normal.squaredNorm() == 0 && r.zero_normals++ == 0) r.first_zero_normal = where(i);
  }

  io::check_attributes(source, points.attributes, points.size(), lines);
  if (r.zero_normals > 0)
    r.warnings.push_back(source + ": " + std::to_string(r.zero_normals) + " point" +
                         (r.zero_normals > 1 ? "s have" : " has") +
                         " a zero normal (the first: " + r.first_zero_normal +
                         "); the reconstruction estimates " +
                         (r.zero_normals > 1 ? "theirs" : "its") + " from the neighbours");
  merge_duplicates(points, lines, r);
  if (r.merged_duplicates > 0) {
    std::string warning = source + ": merged " + std::to_string(r.merged_duplicates) +
                          " duplicate point" + (r.merged_duplicates > 1 ? "s" : "") +
                          " (exactly equal positions; the first of each is kept";
    if (r.merged_with_other_normal > 0) {
      warning += ", with its normal, although " + std::to_string(r.merged_with_other_normal) +
                 " of the merged had another";
    }
    warning += "); " + std::to_string(points.size()) + " points remain";
    r.warnings.push_back(warning);
  }

  const std::size_t n = points.size();
  if (n == 1 && r.points_read > 1) {
    fail(source, "all " + std::to_string(r.points_read) + " points are at the same position " +
                     vector_text(points.points[0]));
  }
  if (n == 0) {
    fail(source, "holds no points; at least " + std::to_string(options.min_points) + " are needed");
  }
  if (n < options.min_points) {
    std::string what = "only " + std::to_string(n) + (r.merged_duplicates ? " distinct" : "") +
                       " point" + (n == 1 ? "" : "s");
    if (r.merged_duplicates) what += " (of " + std::to_string(r.points_read) + ")";
    fail(source, what + "; at least " + std::to_string(options.min_points) + " are needed");
  }

  if (const std::string problem = spread_problem(points.points, options); !problem.empty()) {
    // A few far points can make the rest look flat or the extent overflow:
    // then they are what is wrong, not the shape.
    const std::vector<std::size_t> far = outliers(points.points);
    if (!far.empty() && n - far.size() >= options.min_points) {
      std::vector<char> is_far(n, 0);
      for (std::size_t i : far) is_far[i] = 1;
      std::vector<Vec3> rest;
      for (std::size_t i = 0; i < n; ++i)
        if (!is_far[i]) rest.push_back(points.points[i]);
      if (spread_problem(rest, options).empty()) {
        const std::size_t farthest = far.front();
        const std::string which = where(farthest) + " at " + vector_text(points.points[farthest]);
        fail(source, (far.size() == 1 ? which + " is an outlier"
                                      : std::to_string(far.size()) +
                                            " points are outliers, the farthest " + which) +
                         ": the other " + std::to_string(rest.size()) + " points span " +
                         short_number(bounding_box(rest).diagonal) + ", all " + std::to_string(n) +
                         " span " + short_number(bounding_box(points.points).diagonal) +
                         "; remove " + (far.size() == 1 ? "it" : "them"));
      }
    }
    fail(source, "all " + std::to_string(n) + " points " + problem);
  }
  return points;
}

void io::check_attributes(const std::string& source, const std::vector<Attribute>& attributes,
                          std::size_t n, const std::vector<std::size_t>& lines) {
  auto where = [&](std::size_t i) {
    const std::string point = "point " + std::to_string(i + 1);
    return lines.empty() ? point : "line " + std::to_string(lines[i]) + " (" + point + ")";
  };
  static const char* const kTypes[] = {"char", "uchar", "short", "ushort",
                                       "int",  "uint",  "float", "double"};
  for (std::size_t a = 0; a < attributes.size(); ++a) {
    const Attribute& attribute = attributes[a];
    const std::string name = "property " + quote(attribute.name);
    if (attribute.name.empty()) fail(source, "an attribute has no name");
    for (std::size_t b = 0; b < a; ++b)
      if (attributes[b].name == attribute.name) fail(source, name + " appears twice");
    if (std::find(std::begin(kTypes), std::end(kTypes), attribute.type) == std::end(kTypes))
      fail(source, name + " has the unknown type " + quote(attribute.type));
    if (attribute.values.size() != n)
      fail(source, name + " has " + std::to_string(attribute.values.size()) + " values for " +
                       std::to_string(n) + " points");
  }
  // Colours are red, green and blue together (alpha optional); a lone channel
  // is an ordinary property.
  for (const Attribute* channel : io::colour_channels(attributes)) {
    const std::string name = "colour property " + quote(channel->name);
    const bool real = channel->type == "float" || channel->type == "double";
    if (!real && channel->type != "uchar" && channel->type != "ushort")
      fail(source, name + " is " + channel->type +
                       "; colours must be uchar (0-255), ushort (0-65535) or float/double (0-1)");
    const double top = channel->type == "uchar" ? 255 : channel->type == "ushort" ? 65535 : 1;
    for (std::size_t i = 0; i < n; ++i) {
      const double v = channel->values[i];
      if (!(v >= 0 && v <= top))
        fail(source, where(i) + ": the " + name + " is " + io::format_double(v) +
                         ", outside 0-" + short_number(top));
    }
  }
  // Every value one its type holds, so that it is written back as it is.
  for (const Attribute& attribute : attributes)
    for (std::size_t i = 0; i < n; ++i)
      if (!io::type_holds(attribute.type, attribute.values[i]))
        fail(source, where(i) + ": property " + quote(attribute.name) + " is a " + attribute.type +
                         ", which cannot hold " + io::format_double(attribute.values[i]));
}

void validate_mesh(const TriangleMesh& mesh, const std::string& source) {
  if (mesh.faces.empty()) throw InputError(source + ": the mesh has no faces");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw InputError(source + ": vertex " + std::to_string(i + 1) +
                       " has a coordinate that is not finite");
  io::check_attributes(source, mesh.attributes, mesh.vertices.size(), {});
  const auto n = static_cast<long long>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int v : mesh.faces[f])
      if (v < 0 || v >= n)
        throw InputError(source + ": face " + std::to_string(f + 1) + " refers to vertex " +
                         std::to_string(v) + ", but the mesh has " + std::to_string(n) +
                         " vertices");
}

void require_normals(const PointSet& points, const std::string& source, const std::string& why) {
  if (!points.has_normals()) io::fail(source, "the points have no normals; " + why);
}

}  // namespace pdd
