#include "pipeline/octree_domain.h"

#include <pdd/errors.h>
#include <pdd/pipeline.h>
#include <pdd/sizing.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <set>
#include <string>

namespace pdd::detail {
namespace {

// A cell is (level, integer coordinates at that level); it is split while it
// holds input points and is above the finest level. Corners are collected
// in integer coordinates of the finest level, so shared nodes appear once.
void collect_nodes(const std::vector<Vec3>& points, const std::vector<int>& inside,
                   const Vec3& origin, double side, int level, int depth,
                   const Eigen::Vector3i& cell, std::set<std::array<long, 3>>& nodes) {
  const long scale = 1L << (depth - level);
  for (int corner = 0; corner < 8; ++corner)
    nodes.insert({(cell.x() + (corner & 1)) * scale, (cell.y() + ((corner >> 1) & 1)) * scale,
                  (cell.z() + ((corner >> 2) & 1)) * scale});
  if (level == depth || inside.empty()) return;
  const double child_side = side / (1L << (level + 1));
  std::array<std::vector<int>, 8> children;
  for (int i : inside) {
    const Vec3 q = (points[i] - origin) / child_side;
    int child = 0;
    for (int k = 0; k < 3; ++k) {
      const long c = std::clamp(static_cast<long>(std::floor(q[k])), 2L * cell[k], 2L * cell[k] + 1);
      child |= static_cast<int>(c - 2L * cell[k]) << k;
    }
    children[child].push_back(i);
  }
  for (int child = 0; child < 8; ++child)
    if (!children[child].empty())
      collect_nodes(points, children[child], origin, side, level + 1, depth,
                    Eigen::Vector3i(2 * cell.x() + (child & 1), 2 * cell.y() + ((child >> 1) & 1),
                                    2 * cell.z() + ((child >> 2) & 1)),
                    nodes);
}

// The octree's cube: the bounding box's largest side, 5 % larger.
double octree_side(const Eigen::AlignedBox3d& box) { return box.sizes().maxCoeff() * 1.05; }

Eigen::AlignedBox3d bounding_box(const PointSet& points) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : points.points) box.extend(p);
  return box;
}

}  // namespace

void insert_octree_nodes(Domain& domain, const PointSet& points, int depth) {
  const Eigen::AlignedBox3d box = bounding_box(points);
  const double side = octree_side(box);
  const Vec3 origin = box.center() - Vec3::Constant(side / 2);
  if (depth <= 0) depth = default_octree_depth(points);
  if (depth > 12) throw InputError("octree domain: depth " + std::to_string(depth) + " is too deep");
  std::vector<int> all(points.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  std::set<std::array<long, 3>> nodes;
  collect_nodes(points.points, all, origin, side, 0, depth, Eigen::Vector3i::Zero(), nodes);
  const double finest = side / (1L << depth);
  std::vector<Vec3> positions;
  positions.reserve(nodes.size());
  // Corners of the coarsest cells can lie outside the domain, far from the
  // data: those are left out. Grid nodes are cospherical by the eight, and
  // their Delaunay triangulation has flat slivers that make the solvers'
  // operators singular; a seeded jitter of 1% of the finest cell removes the
  // degeneracy without changing the resolution.
  std::mt19937_64 rng(depth);
  std::uniform_real_distribution<double> jitter(-0.01 * finest, 0.01 * finest);
  for (const auto& n : nodes) {
    const Vec3 p = origin + finest * Vec3(n[0], n[1], n[2]) +
                   Vec3(jitter(rng), jitter(rng), jitter(rng));
    if (domain.locate(p).tet >= 0) positions.push_back(p);
  }
  domain.insert(positions);
}

}  // namespace pdd::detail

namespace pdd {

int default_octree_depth(const PointSet& points) {
  const double side = detail::octree_side(detail::bounding_box(points));
  return std::max(1, static_cast<int>(std::ceil(std::log2(side / average_spacing(points)))));
}

}  // namespace pdd
