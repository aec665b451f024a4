// Normal estimation by jet fitting (CGAL Point_set_processing_3).
#include <pdd/errors.h>
#include <pdd/normals.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/jet_estimate_normals.h>

#include <utility>

namespace pdd {

std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int neighbors,
                                   const std::string& source) {
  if (points.size() < kMinPointsForNormals)
    throw InputError(source + ": " + std::to_string(points.size()) +
                     " points are too few to estimate normals from (at least " +
                     std::to_string(kMinPointsForNormals) + " are needed)");
  using Kernel = CGAL::Simple_cartesian<double>;
  using Pair = std::pair<Kernel::Point_3, Kernel::Vector_3>;
  std::vector<Pair> pairs;
  pairs.reserve(points.size());
  for (const Vec3& p : points) pairs.emplace_back(Kernel::Point_3(p.x(), p.y(), p.z()),
                                                  Kernel::Vector_3(0, 0, 0));
  const auto k = static_cast<unsigned>(std::min<std::size_t>(neighbors, points.size() - 1));
  CGAL::jet_estimate_normals<CGAL::Parallel_if_available_tag>(
      pairs, k,
      CGAL::parameters::point_map(CGAL::First_of_pair_property_map<Pair>())
          .normal_map(CGAL::Second_of_pair_property_map<Pair>()));
  std::vector<Vec3> normals;
  normals.reserve(pairs.size());
  for (const Pair& p : pairs) {
    Vec3 n(p.second.x(), p.second.y(), p.second.z());
    // A neighbourhood that is a line or a point gives no plane: say so rather
    // than hand the solver a zero or NaN normal.
    const double length = n.norm();
    if (!(length > 0) || !std::isfinite(length))
      throw InputError(source + ": the neighbourhood of point " +
                       std::to_string(normals.size() + 1) +
                       " is too flat or too degenerate to estimate a normal from");
    normals.push_back(n / length);
  }
  return normals;
}

}  // namespace pdd
