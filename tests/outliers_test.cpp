#include <pdd/errors.h>
#include <pdd/outliers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "support/shapes.h"

namespace pdd {
namespace {

// `count` points uniform in the cube [-1.3, 1.3]^3, seeded.
std::vector<Vec3> uniform_points(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

TEST(Outliers, FarPointsAreFoundAndTheSurfaceIsKept) {
  std::vector<Vec3> points = test::sample_sphere(5000).points;
  const std::size_t surface = points.size();
  // Points at least 0.4 off the sphere: 4 times the mean distance of a
  // surface point to its 16 nearest (sampling spacing 0.05).
  for (const Vec3& p : uniform_points(400, 3))
    if (std::abs(p.norm() - 1) > 0.4) points.push_back(p);
  OutlierReport report;
  const std::vector<char> outlier = find_outliers(points, {}, &report);
  std::size_t surface_flagged = 0, caught = 0;
  for (std::size_t i = 0; i < points.size(); ++i) (i < surface ? surface_flagged : caught) += outlier[i];
  const std::size_t strays = points.size() - surface;
  std::cout << caught << " of " << strays << " strays caught\n";
  EXPECT_EQ(surface_flagged, 0u);
  // Strays whose neighbours are strays vouch for each other up to 6 times the
  // typical spacing (the cap of the local reference): most are caught, not all.
  EXPECT_GT(caught, 0.7 * static_cast<double>(strays));
  EXPECT_EQ(report.removed, caught);
  EXPECT_EQ(report.ratio, 3);
  EXPECT_EQ(report.neighbors, 16);
  EXPECT_GT(report.median_spacing, 0);
}

TEST(Outliers, VaryingDensityAndNoiseAreNotOutliers) {
  // A sphere sampled 9 times more densely on one half, with noise.
  PointSet dense = test::sample_sphere(9000);
  std::vector<Vec3> points;
  for (const Vec3& p : dense.points)
    if (p.z() > 0) points.push_back(p);
  for (const Vec3& p : test::sample_sphere(1000).points)
    if (p.z() <= 0) points.push_back(p);
  PointSet noisy;
  noisy.points = points;
  test::add_noise(noisy, 0.005, 1);
  const std::vector<char> outlier = find_outliers(noisy.points);
  EXPECT_EQ(std::count(outlier.begin(), outlier.end(), 1), 0);
}

TEST(Outliers, OffTooFewPointsAndBadOptions) {
  const std::vector<Vec3> points = test::sample_sphere(10).points;
  const std::vector<char> few = find_outliers(points);
  EXPECT_EQ(std::count(few.begin(), few.end(), 1), 0);
  OutlierOptions off;
  off.ratio = 0;
  const std::vector<Vec3> many = test::sample_sphere(100).points;
  OutlierReport report;
  find_outliers(many, off, &report);
  EXPECT_EQ(report.removed, 0u);
  OutlierOptions bad;
  bad.ratio = -1;
  EXPECT_THROW(find_outliers(many, bad), InputError);
  bad.ratio = 3;
  bad.neighbors = 0;
  EXPECT_THROW(find_outliers(many, bad), InputError);
}

}  // namespace
}  // namespace pdd
