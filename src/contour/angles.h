// The smallest angle of a triangle, shared by the contour stage's clean-up,
// trim and rim remeshing (private to src/contour).
#pragma once

#include <pdd/types.h>

#include <algorithm>
#include <cmath>

namespace pdd::detail {

// In degrees: the angle opposite the shortest edge (the smallest one), by
// atan2, which stays accurate near 0 and 180 where acos does not. One atan2
// instead of three: the clean-up's relaxation calls this 36 times per vertex.
inline double min_angle_degrees(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  const Vec3& apex = bc <= ab && bc <= ca ? a : (ca <= ab ? b : c);
  const Vec3& u = &apex == &a ? b : (&apex == &b ? c : a);
  const Vec3& w = &apex == &a ? c : (&apex == &b ? a : b);
  const Vec3 x = u - apex, y = w - apex;
  return std::atan2(x.cross(y).norm(), x.dot(y)) * (180 / M_PI);
}

}  // namespace pdd::detail
