// The range of extents at which a mesh's measures (angles, areas, distances)
// are computed without overflow or underflow.
#include <pdd/errors.h>
#include <pdd/quality.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

#include "metrics/elements.h"

namespace pdd {

void require_measurable(const TriangleMesh& mesh, const std::string& source) {
  // Squares and cross products of lengths up to the extent must stay within
  // a double's range (about 1e-308 to 1e308), with room for sums of them.
  constexpr double kLargest = 1e150;
  constexpr double kSmallest = 1e-150;
  detail::check_indices(mesh.faces, mesh.vertices.size(), "face");
  if (mesh.faces.empty()) return;
  Vec3 lo = mesh.vertices[mesh.faces[0][0]], hi = lo;
  for (const auto& f : mesh.faces)
    for (const int v : f) {
      lo = lo.cwiseMin(mesh.vertices[v]);
      hi = hi.cwiseMax(mesh.vertices[v]);
    }
  const double extent = (hi - lo).stableNorm();  // inf when hi - lo overflows
  if (extent <= kLargest && (extent >= kSmallest || extent == 0)) return;
  char span[64] = "more than a double holds";
  if (std::isfinite(extent)) std::snprintf(span, sizeof span, "%.3g", extent);
  char what[240];
  std::snprintf(what, sizeof what,
                ": the vertices span %s%s (bounding-box diagonal), %s than the %g at which "
                "angles, areas and distances can be computed",
                extent > kLargest ? "" : "only ", span, extent > kLargest ? "more" : "less",
                extent > kLargest ? kLargest : kSmallest);
  throw InputError(source + what);
}

}  // namespace pdd
