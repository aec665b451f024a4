#include "support/figure2_layouts.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "support/shapes.h"

namespace pdd::test {
namespace {

// n directions uniform on the unit sphere.
std::vector<Vec3> random_directions(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<Vec3> directions;
  directions.reserve(n);
  while (static_cast<int>(directions.size()) < n) {
    const Vec3 g(gauss(rng), gauss(rng), gauss(rng));
    if (g.norm() > 1e-9) directions.push_back(g.normalized());
  }
  return directions;
}

}  // namespace

const char* figure2_label(Figure2Layout layout) {
  switch (layout) {
    case Figure2Layout::kBiasedRandom:
      return "(a) biased random";
    case Figure2Layout::kUnbiasedRandom:
      return "(b) unbiased random";
    case Figure2Layout::kBiasedEven:
      return "(c) biased even";
    case Figure2Layout::kUnbiasedEven:
      return "(d) unbiased even";
    case Figure2Layout::kUnbiasedEvenAligned:
      return "(d') unbiased even, aligned";
  }
  return "";
}

Domain figure2_domain(Figure2Layout layout, int points_per_layer, unsigned seed) {
  const bool biased =
      layout == Figure2Layout::kBiasedRandom || layout == Figure2Layout::kBiasedEven;
  const double inner = biased ? 0.95 : 0.9;
  const double outer = biased ? 1.15 : 1.1;

  std::vector<Vec3> inner_directions, outer_directions;
  if (layout == Figure2Layout::kBiasedRandom || layout == Figure2Layout::kUnbiasedRandom) {
    inner_directions = random_directions(points_per_layer, seed);
    outer_directions = random_directions(points_per_layer, seed + 1);
  } else {
    // sample_sphere is the Fibonacci lattice about the z axis.
    inner_directions = sample_sphere(points_per_layer).points;
    outer_directions = inner_directions;
    if (layout != Figure2Layout::kUnbiasedEvenAligned) {
      const Eigen::AngleAxisd half_golden_turn(0.5 * M_PI * (3.0 - std::sqrt(5.0)), Vec3::UnitZ());
      for (Vec3& d : outer_directions) d = half_golden_turn * d;
    }
  }
  std::vector<Vec3> points;
  points.reserve(2 * points_per_layer);
  for (const Vec3& d : inner_directions) points.push_back(inner * d);
  for (const Vec3& d : outer_directions) points.push_back(outer * d);

  Domain domain(points);
  std::vector<double> f;
  f.reserve(domain.num_vertices());
  for (const Vec3& p : domain.vertices()) f.push_back(p.norm() - 1.0);
  domain.set_f(std::move(f));
  return domain;
}

}  // namespace pdd::test
