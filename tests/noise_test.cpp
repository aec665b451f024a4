// The noise estimate and the SSD value weight chosen from it (solvers.h):
// the estimate must see the noise added to a sphere and not its curvature,
// and the weight must fall as the noise grows, up to its cap on clean input.
#include <pdd/errors.h>
#include <pdd/solvers.h>

#include "support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace pdd {
namespace {

// 20k points on the unit sphere (largest side l = 2), with Gaussian noise of
// standard deviation sigma on each coordinate.
PointSet noisy_sphere(double sigma) {
  PointSet points = test::sample_sphere(20000);
  if (sigma > 0) test::add_noise(points, sigma, 11);
  return points;
}

TEST(Noise, TheEstimateFollowsTheNoiseAndIgnoresTheCurvature) {
  const double clean = estimate_noise(noisy_sphere(0));
  const double low = estimate_noise(noisy_sphere(0.005));
  const double high = estimate_noise(noisy_sphere(0.01));
  std::cout << "noise estimate: clean " << clean << ", sigma 0.005: " << low
            << ", sigma 0.01: " << high << "\n";
  // The sphere's own curvature over a neighbourhood: far under either noise.
  EXPECT_LT(clean, 0.05 * 0.005);
  // The neighbourhoods' fits absorb part of the noise, the more so the
  // larger it is against the spacing (about 0.025 here).
  EXPECT_GT(low, 0.4 * 0.005);
  EXPECT_LT(low, 1.2 * 0.005);
  EXPECT_GT(high, 0.3 * 0.01);
  EXPECT_LT(high, 1.2 * 0.01);
  EXPECT_GT(high, 1.2 * low);
}

TEST(Noise, PastTheSampleSizeTheStridedEstimateStillFollowsTheNoise) {
  // 150k points: the quartile is taken over every third one
  // (statistics_sample.h), their neighbourhoods from all of them. The same
  // sphere and noise as a denser sample, so that the estimate is nearer the
  // noise than at 20k (spacing 0.008 against 0.025).
  PointSet dense = test::sample_sphere(150000);
  const double clean = estimate_noise(dense);
  test::add_noise(dense, 0.005, 11);
  const double noisy = estimate_noise(dense);
  std::cout << "noise estimate at 150k points: clean " << clean << ", sigma 0.005: " << noisy
            << "\n";
  EXPECT_LT(clean, 0.05 * 0.005);
  EXPECT_GT(noisy, 0.6 * 0.005);
  EXPECT_LT(noisy, 1.2 * 0.005);
}

TEST(Noise, TheValueWeightIsKOverTheRelativeNoiseSquaredUpToItsCap) {
  EXPECT_DOUBLE_EQ(ssd_value_weight(0.01, 2.0), kSsdValueWeightNoiseScale / (0.005 * 0.005));
  EXPECT_DOUBLE_EQ(ssd_value_weight(0.02, 4.0), ssd_value_weight(0.01, 2.0));  // scale-free
  EXPECT_DOUBLE_EQ(ssd_value_weight(0.0, 2.0), kSsdMaxValueWeight);
  EXPECT_DOUBLE_EQ(ssd_value_weight(1e-6, 2.0), kSsdMaxValueWeight);
  const double sphere = 2.0;  // largest side of noisy_sphere's bounding box
  EXPECT_DOUBLE_EQ(ssd_value_weight(estimate_noise(noisy_sphere(0)), sphere), kSsdMaxValueWeight);
  const double low = ssd_value_weight(estimate_noise(noisy_sphere(0.005)), sphere);
  const double high = ssd_value_weight(estimate_noise(noisy_sphere(0.01)), sphere);
  std::cout << "value weight: sigma 0.005: " << low << ", sigma 0.01: " << high << "\n";
  EXPECT_LT(low, kSsdMaxValueWeight);
  EXPECT_LT(high, low);
}

// K (l / s)^3 up to its cap, s the noise while it is under r0 spacings, at
// least F spacings from r1 spacings on, continuous in between.
TEST(Noise, TheSpectralWeightSmoothsNoiseAtTheSpacingOverAFractionOfIt) {
  const auto [r0, r1] = kSpectralSmoothedNoise;
  const double F = kSpectralSmoothingSpacings, l = 2.0, h = 0.01;
  const auto plain = [&](double s) {
    return std::min(kSpectralValueWeightNoiseScale * std::pow(l / s, 3), kSpectralMaxValueWeight);
  };
  EXPECT_DOUBLE_EQ(spectral_value_weight(0.5 * r0 * h, h, l), plain(0.5 * r0 * h));
  EXPECT_DOUBLE_EQ(spectral_value_weight(r0 * h, h, l), plain(r0 * h));
  EXPECT_DOUBLE_EQ(spectral_value_weight(r1 * h, h, l), plain(F * h));
  EXPECT_DOUBLE_EQ(spectral_value_weight(2 * F * h, h, l), plain(2 * F * h));  // the noise itself
  EXPECT_DOUBLE_EQ(spectral_value_weight(r1 * h, 0, l), plain(r1 * h));  // no spacing: no floor
  EXPECT_DOUBLE_EQ(spectral_value_weight(0, h, l), kSpectralMaxValueWeight);
  // Continuous and never rising with the noise across the ramp.
  double previous = spectral_value_weight(r0 * h, h, l);
  for (int i = 1; i <= 100; ++i) {
    const double w = spectral_value_weight((r0 + (1.2 * r1 - r0) * i / 100) * h, h, l);
    EXPECT_LE(w, previous);
    EXPECT_GT(w, 0.5 * previous);
    previous = w;
  }
}

TEST(Noise, TooFewNeighboursForACubicFitIsAnInputError) {
  EXPECT_THROW(estimate_noise(noisy_sphere(0), 10), InputError);
  PointSet few = test::sample_sphere(15);
  EXPECT_EQ(estimate_noise(few), 0.0);  // fewer points than neighbours: nothing to measure
}

}  // namespace
}  // namespace pdd
