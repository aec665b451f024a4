// Normal orientation by minimum-spanning-tree propagation (CGAL
// Point_set_processing_3), and random flips for the experiments.
#include <pdd/normals.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/mst_orient_normals.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "common/nearest_neighbors.h"
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

namespace pdd {
namespace {

// Union-find whose links carry a parity: whether a point's normal must be
// flipped to agree with its root's.
struct SignedUnionFind {
  std::vector<int> parent;
  std::vector<std::uint8_t> parity;
  explicit SignedUnionFind(std::size_t n) : parent(n), parity(n, 0) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<int>(i);
  }
  std::pair<int, std::uint8_t> find(int i) {
    std::uint8_t p = 0;
    int r = i;
    while (parent[r] != r) {
      p ^= parity[r];
      r = parent[r];
    }
    // Path compression, keeping each node's parity to the root.
    std::uint8_t q = p;
    while (parent[i] != r) {
      const int next = parent[i];
      const std::uint8_t own = parity[i];
      parent[i] = r;
      parity[i] = q;
      q ^= own;
      i = next;
    }
    return {r, p};
  }
};

}  // namespace

std::vector<int> orient_segments(const std::vector<Vec3>& points, std::vector<Vec3>& normals,
                                 int neighbors, const std::vector<double>* votes) {
  const detail::NearestNeighbors knn(points);
  struct Edge {
    double alignment;  // |n_i . n_j|
    double tilt;       // the larger |d . n| of the step d from i to j
    int i, j;
  };
  std::vector<Edge> reliable, others;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const int j : knn.query(points[i], neighbors + 1)) {
      if (j <= static_cast<int>(i)) continue;
      const double alignment = std::abs(normals[i].dot(normals[j]));
      const Vec3 d = (points[j] - points[i]).normalized();
      const double tilt = std::max(std::abs(d.dot(normals[i])), std::abs(d.dot(normals[j])));
      // A reliable link: nearly parallel normals, and a step along both
      // tangent planes, not across a thin part between two sheets.
      (alignment >= 0.9 && tilt <= 0.2 ? reliable : others)
          .push_back({alignment, tilt, static_cast<int>(i), j});
    }
  std::stable_sort(reliable.begin(), reliable.end(),
                   [](const Edge& a, const Edge& b) { return a.alignment > b.alignment; });
  SignedUnionFind sets(points.size());
  std::vector<std::size_t> size(points.size(), 1);
  // Each segment's votes, summed in its root's orientation.
  std::vector<double> vote = votes ? *votes : std::vector<double>();
  const auto confident = [&](int root, double v) {
    return size[root] > static_cast<std::size_t>(2 * neighbors) &&
           std::abs(v) >= kConfidentVote * static_cast<double>(size[root]);
  };
  const auto join = [&](const Edge& e, std::size_t below) {
    const auto [ri, pi] = sets.find(e.i);
    const auto [rj, pj] = sets.find(e.j);
    if (ri == rj || std::min(size[ri], size[rj]) >= below) return;
    const std::uint8_t opposite = normals[e.i].dot(normals[e.j]) < 0;
    const std::uint8_t parity = pi ^ pj ^ opposite;
    if (votes) {
      // Two segments whose own votes are clear and say the link is wrong stay
      // apart: one wrong link would otherwise turn a whole region.
      const double vj = parity ? -vote[rj] : vote[rj];
      if (confident(ri, vote[ri]) && confident(rj, vj) && (vote[ri] > 0) != (vj > 0)) return;
      vote[ri] += vj;
    }
    sets.parent[rj] = ri;
    sets.parity[rj] = parity;
    size[ri] += size[rj];
  };
  for (const Edge& e : reliable) join(e, points.size() + 1);
  // Segments smaller than a neighbourhood (a noisy point, a crease's few
  // points) would be turned by a vote of a few samples: they join a
  // neighbouring segment through their most tangential link of roughly
  // parallel normals instead.
  others.erase(std::remove_if(others.begin(), others.end(),
                              [](const Edge& e) { return e.alignment < 0.5; }),
               others.end());
  std::stable_sort(others.begin(), others.end(),
                   [](const Edge& a, const Edge& b) { return a.tilt < b.tilt; });
  for (const Edge& e : others) join(e, static_cast<std::size_t>(neighbors) + 1);
  std::vector<int> segment(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [root, parity] = sets.find(static_cast<int>(i));
    segment[i] = root;
    if (parity) normals[i] = -normals[i];
  }
  return segment;
}

}  // namespace pdd
