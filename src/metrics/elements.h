// Private to src/metrics: helpers shared by the quality measures.
#pragma once

#include <pdd/types.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pdd::detail {

// Throws std::invalid_argument naming the first element that indexes a
// vertex outside [0, num_vertices).
template <typename Element>
void check_indices(const std::vector<Element>& elements, std::size_t num_vertices,
                   const char* what) {
  const int n = static_cast<int>(num_vertices);
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (const int v : elements[i])
      if (v < 0 || v >= n)
        throw std::invalid_argument(std::string(what) + " " + std::to_string(i) +
                                    " references vertex " + std::to_string(v) + " of " +
                                    std::to_string(n));
}

// Angle between u and v in degrees, 0 when either vanishes (atan2(0, -0)
// would be 180); atan2 stays accurate near 0 and 180 where acos does not.
inline double angle_degrees(const Vec3& u, const Vec3& v) {
  if (u.isZero(0) || v.isZero(0)) return 0;
  return std::atan2(u.cross(v).norm(), u.dot(v)) * (180.0 / M_PI);
}

}  // namespace pdd::detail
