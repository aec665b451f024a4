// The smallest angle of a triangle, shared by the contour stage's clean-up,
// trim and rim remeshing (private to src/contour).
#pragma once

#include <pdd/types.h>

#include <algorithm>
#include <cmath>

namespace pdd::detail {

// In degrees; atan2 stays accurate near 0 and 180 where acos does not.
inline double min_angle_degrees(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * (180 / M_PI);
}

}  // namespace pdd::detail
