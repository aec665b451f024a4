// Angles of surface triangles (§2.2, Figure 2: the quality of contoured meshes).
#include <pdd/quality.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "metrics/elements.h"

namespace pdd {
namespace {

// The three angles of every face, computed in parallel.
std::vector<std::array<double, 3>> face_angles(const TriangleMesh& mesh) {
  detail::check_indices(mesh.faces, mesh.vertices.size(), "face");
  std::vector<std::array<double, 3>> angles(mesh.faces.size());
  tbb::parallel_for(std::size_t(0), mesh.faces.size(), [&](std::size_t i) {
    const auto& f = mesh.faces[i];
    angles[i] = triangle_angles(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]);
  });
  return angles;
}

double smallest(const std::array<double, 3>& a) { return std::min({a[0], a[1], a[2]}); }

}  // namespace

std::array<double, 3> triangle_angles(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {detail::angle_degrees(b - a, c - a), detail::angle_degrees(c - b, a - b),
          detail::angle_degrees(a - c, b - c)};
}

std::vector<double> min_angles(const TriangleMesh& mesh) {
  const auto angles = face_angles(mesh);
  std::vector<double> result(angles.size());
  std::transform(angles.begin(), angles.end(), result.begin(), smallest);
  return result;
}

TriangleQuality triangle_quality(const TriangleMesh& mesh) {
  const auto angles = face_angles(mesh);
  std::vector<double> per_face(angles.size());
  std::transform(angles.begin(), angles.end(), per_face.begin(), smallest);
  TriangleQuality q;
  q.count = per_face.size();
  q.min_angle_histogram = histogram(per_face, 0.0, 60.0, 12);
  if (q.count == 0) return q;
  q.min_angle = std::numeric_limits<double>::infinity();
  std::size_t below[3] = {0, 0, 0};
  double sum = 0;
  for (std::size_t i = 0; i < q.count; ++i) {
    const double m = per_face[i];
    q.min_angle = std::min(q.min_angle, m);
    q.max_angle = std::max({q.max_angle, angles[i][0], angles[i][1], angles[i][2]});
    sum += m;
    for (int k = 0; k < 3; ++k)
      if (m < 10.0 * (k + 1)) ++below[k];
  }
  const double n = static_cast<double>(q.count);
  q.mean_min_angle = sum / n;
  q.fraction_below_10 = below[0] / n;
  q.fraction_below_20 = below[1] / n;
  q.fraction_below_30 = below[2] / n;
  return q;
}

}  // namespace pdd
