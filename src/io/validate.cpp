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
  std::size_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    points.points[out] = points.points[i];
    if (points.has_normals()) points.normals[out] = points.normals[i];
    if (!lines.empty()) lines[out] = lines[i];
    ++out;
  }
  points.points.resize(out);
  if (points.has_normals()) points.normals.resize(out);
  if (!lines.empty()) lines.resize(out);
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
    if (normal.squaredNorm() == 0) {
      fail(source, where(i) + ": the normal " + vector_text(normal) + " has zero length");
    }
  }

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

  // Degenerate spread, relative to the bounding box.
  Vec3 lo = points.points[0];
  Vec3 hi = lo;
  for (const Vec3& p : points.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double tolerance = options.flatness_tolerance;
  if (diagonal <= tolerance * magnitude) {
    fail(source, "all " + std::to_string(n) + " points coincide: their bounding box diagonal, " +
                     short_number(diagonal) + ", is within a relative " + short_number(tolerance) +
                     " of their coordinates (" + short_number(magnitude) + ")");
  }
  // The thinnest extents, along the principal axes of the points: an upper
  // bound of the true thinnest extents, so a set rejected here is truly flat.
  Vec3 center = Vec3::Zero();
  for (const Vec3& p : points.points) center += p;
  center /= static_cast<double>(n);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points.points) covariance += (p - center) * (p - center).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  auto extent = [&](int axis) {  // eigenvalues ascend
    const Vec3 direction = eigen.eigenvectors().col(axis);
    double a = INFINITY;
    double b = -INFINITY;
    for (const Vec3& p : points.points) {
      const double t = (p - center).dot(direction);
      a = std::min(a, t);
      b = std::max(b, t);
    }
    return b - a;
  };
  const double thickness = extent(0);
  if (thickness <= tolerance * diagonal) {
    const bool on_a_line = extent(1) <= tolerance * diagonal;
    fail(source, "all " + std::to_string(n) + " points lie " +
                     (on_a_line ? "on one line" : "in one plane") + " (thickness " +
                     short_number(thickness) + " for a bounding box diagonal of " +
                     short_number(diagonal) + "; relative tolerance " + short_number(tolerance) +
                     "); they cannot bound a volume");
  }
  return points;
}

void validate_mesh(const TriangleMesh& mesh, const std::string& source) {
  if (mesh.faces.empty()) throw InputError(source + ": the mesh has no faces");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw InputError(source + ": vertex " + std::to_string(i + 1) +
                       " has a coordinate that is not finite");
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
