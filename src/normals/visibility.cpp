// Orientation votes by ray shooting: the side of a surface from which more of
// the space around it is open to infinity is its outside (the visibility
// signs of Mullen et al. 2010, "Signing the unsigned"). Hand-written: CGAL's
// and Open3D's ray queries need a mesh or primitives, and the points have
// neither yet; a ray marched through a grid of the cells the points occupy
// is all that is asked here.
#include <pdd/normals.h>

#include "common/nearest_neighbors.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pdd {
namespace {

constexpr int kRays = 16;            // per side of each sample
constexpr int kRadiusNeighbors = 6;  // a point blocks rays within its mean distance to these
constexpr double kSkip = 3;          // radii a ray travels (out of its own sheet) unblocked
constexpr std::uint64_t kMaxCells = std::uint64_t(1) << 28;  // 32 MB of bits

struct Occupancy {
  Vec3 low;
  double cell = 0;
  std::int64_t dims[3] = {0, 0, 0};
  std::vector<std::uint64_t> bits;

  bool inside(const std::int64_t c[3]) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < dims[0] && c[1] < dims[1] &&
           c[2] < dims[2];
  }
  std::uint64_t index(const std::int64_t c[3]) const {
    return (static_cast<std::uint64_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
  }
  void cell_of(const Vec3& p, std::int64_t c[3]) const {
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<std::int64_t>(std::floor((p[a] - low[a]) / cell));
  }
  bool occupied(const std::int64_t c[3]) const {
    const std::uint64_t i = index(c);
    return (bits[i >> 6] >> (i & 63)) & 1;
  }
};

// The cells within each point's radius (a cube): where the points are sparser
// their splats are larger, so that rays do not pass between them.
Occupancy occupy(const std::vector<Vec3>& points, const std::vector<double>& radius, double cell) {
  Vec3 low = points.front(), high = points.front();
  for (const Vec3& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  Occupancy grid;
  const Vec3 extent = high - low;
  for (;;) {
    std::uint64_t cells = 1;
    for (int a = 0; a < 3; ++a) cells *= static_cast<std::uint64_t>(extent[a] / cell) + 5;
    if (cells <= kMaxCells) break;
    cell *= 1.25;  // a coarser grid rather than more memory than the run's
  }
  grid.cell = cell;
  grid.low = low - Vec3::Constant(2 * cell);
  for (int a = 0; a < 3; ++a) grid.dims[a] = static_cast<std::int64_t>(extent[a] / cell) + 5;
  grid.bits.assign((grid.dims[0] * grid.dims[1] * grid.dims[2] + 63) / 64, 0);
  std::int64_t lo[3], hi[3], c[3];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 r = Vec3::Constant(std::min(radius[i], 2 * cell * kSkip));
    grid.cell_of(points[i] - r, lo);
    grid.cell_of(points[i] + r, hi);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(lo[a], 0);
      hi[a] = std::min<std::int64_t>(hi[a], grid.dims[a] - 1);
    }
    for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2])
      for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
        for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0]) {
          const std::uint64_t k = grid.index(c);
          grid.bits[k >> 6] |= std::uint64_t(1) << (k & 63);
        }
  }
  return grid;
}

// The share of kRays rays around `axis` (cosine-weighted, on a spherical
// Fibonacci pattern, so deterministic) that leave the grid unblocked.
double open_share(const Occupancy& grid, const Vec3& origin, const Vec3& axis, double skip) {
  const Vec3 a = axis.unitOrthogonal();
  const Vec3 b = axis.cross(a);
  const double golden = M_PI * (3 - std::sqrt(5.0));
  int open = 0;
  for (int k = 0; k < kRays; ++k) {
    const double u = (k + 0.5) / kRays;
    const double r = std::sqrt(u), phi = golden * k;
    const Vec3 d = r * std::cos(phi) * a + r * std::sin(phi) * b + std::sqrt(1 - u) * axis;
    bool blocked = false;
    std::int64_t c[3];
    for (double t = skip;; t += 0.5 * grid.cell) {
      grid.cell_of(origin + t * d, c);
      if (!grid.inside(c)) break;
      if (grid.occupied(c)) {
        blocked = true;
        break;
      }
    }
    open += !blocked;
  }
  return static_cast<double>(open) / kRays;
}

}  // namespace

std::vector<double> visibility_votes(const std::vector<Vec3>& points,
                                     const std::vector<Vec3>& normals,
                                     const std::vector<std::size_t>& samples) {
  std::vector<double> votes(samples.size(), 0.0);
  if (points.empty() || samples.empty()) return votes;
  const detail::NearestNeighbors knn(points);
  std::vector<double> radius(points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
    double sum = 0;
    const std::vector<int> near = knn.query(points[i], kRadiusNeighbors + 1);
    for (const int j : near) sum += (points[j] - points[i]).norm();
    radius[i] = sum / std::max<double>(1, static_cast<double>(near.size()) - 1);
  });
  double spacing = 0;  // the average spacing (as average_spacing, sizing.h), summed in order
  for (const double r : radius) spacing += r / static_cast<double>(points.size());
  const Occupancy grid = occupy(points, radius, 1.5 * spacing);
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t s) {
    const Vec3& p = points[samples[s]];
    const Vec3& n = normals[samples[s]];
    const double skip = kSkip * std::max(grid.cell, radius[samples[s]]);
    votes[s] = open_share(grid, p, n, skip) - open_share(grid, p, -n, skip);
  });
  return votes;
}

}  // namespace pdd
