// Normal orientation by minimum-spanning-tree propagation (CGAL
// Point_set_processing_3), and random flips for the experiments.
#include <pdd/normals.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/mst_orient_normals.h>

#include <algorithm>
#include <random>
#include <tuple>

namespace pdd {

std::size_t orient_normals_mst(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                               int neighbors, std::size_t* unreached) {
  using Kernel = CGAL::Simple_cartesian<double>;
  // (point, normal, index): CGAL moves the points it could not orient to the end.
  using Item = std::tuple<Kernel::Point_3, Kernel::Vector_3, std::size_t>;
  std::vector<Item> items;
  items.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    items.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
                       Kernel::Vector_3(normals[i].x(), normals[i].y(), normals[i].z()), i);
  // CGAL orients the component of the k-nearest-neighbour graph that holds the
  // highest point and moves the others to the end; each further component is
  // oriented the same way from its own highest point.
  auto begin = items.begin();
  while (items.end() - begin >= 3) {
    const auto remaining = static_cast<std::size_t>(items.end() - begin);
    const auto k = static_cast<unsigned>(std::min<std::size_t>(neighbors, remaining - 1));
    std::vector<Item> part(begin, items.end());
    const auto first_unoriented = CGAL::mst_orient_normals(
        part, k,
        CGAL::parameters::point_map(CGAL::Nth_of_tuple_property_map<0, Item>())
            .normal_map(CGAL::Nth_of_tuple_property_map<1, Item>()));
    std::copy(part.begin(), part.end(), begin);
    if (first_unoriented == part.begin()) break;  // no progress: leave the rest as it is
    begin += first_unoriented - part.begin();
  }
  if (unreached) *unreached = static_cast<std::size_t>(items.end() - begin);
  std::size_t flipped = 0;
  for (auto it = items.begin(); it != begin; ++it) {
    const std::size_t i = std::get<2>(*it);
    const Kernel::Vector_3& n = std::get<1>(*it);
    if (n.x() * normals[i].x() + n.y() * normals[i].y() + n.z() * normals[i].z() < 0) {
      normals[i] = -normals[i];
      ++flipped;
    }
  }
  return flipped;
}

void flip_random_normals(std::vector<Vec3>& normals, double fraction, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (Vec3& n : normals)
    if (uniform(random) < fraction) n = -n;
}

}  // namespace pdd
