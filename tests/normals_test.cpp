// Normals for point sets without them or with untrusted signs (normals.h and
// the run's first step, pipeline.h): estimation accuracy, orientation, and
// reconstructions of generated shapes from bare points.
#include <pdd/errors.h>
#include <pdd/normals.h>
#include <pdd/pipeline.h>
#include <pdd/quality.h>
#include <pdd/report.h>
#include <pdd/solvers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/shapes.h"

namespace pdd {
namespace {

double degrees_between_lines(const Vec3& a, const Vec3& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180 / M_PI;
}

ReconstructOptions bare_options(double edge, Orientation orientation = Orientation::kMst) {
  ReconstructOptions o;
  o.target_edge_length = edge;
  o.orientation = orientation;
  return o;
}

PointSet without_normals(PointSet points) {
  points.normals.clear();
  return points;
}

TEST(Normals, JetFittingOnASphereIsWithinADegreeOfTheTruth) {
  const PointSet sphere = test::sample_sphere(3000);
  const std::vector<Vec3> estimated = estimate_normals(sphere.points, 18, "sphere");
  ASSERT_EQ(estimated.size(), sphere.size());
  double worst = 0;
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    EXPECT_NEAR(estimated[i].norm(), 1.0, 1e-12);
    worst = std::max(worst, degrees_between_lines(estimated[i], sphere.normals[i]));
  }
  EXPECT_LT(worst, 1.0);
}

// One fit gives both: the points projected onto their jets lie nearer the
// sphere than the noisy input, and their normals are near the radial ones.
TEST(Normals, OneJetFitSmoothsThePointsAndGivesTheirNormals) {
  PointSet sphere = test::sample_sphere(3000);
  test::add_noise(sphere, 0.01, 3);
  const JetFits fits = fit_jets(sphere.points, 60, "sphere");
  ASSERT_EQ(fits.points.size(), sphere.size());
  ASSERT_EQ(fits.normals.size(), sphere.size());
  double before = 0, after = 0;
  for (std::size_t i = 0; i < sphere.size(); ++i) {
    before += std::pow(sphere.points[i].norm() - 1, 2);
    after += std::pow(fits.points[i].norm() - 1, 2);
    EXPECT_LT(degrees_between_lines(fits.normals[i], fits.points[i]), 5.0) << i;
  }
  EXPECT_LT(after, 0.25 * before);  // RMS off the sphere at most half the noise's
}

// Points on the faces of the cube [-1, 1]^3, with the faces' normals.
PointSet sample_cube(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  PointSet cube;
  for (int i = 0; i < n; ++i) {
    const int face = i % 6, axis = face / 2;
    Vec3 p(uniform(random), uniform(random), uniform(random));
    p[axis] = face % 2 ? 1.0 : -1.0;
    cube.points.push_back(p);
    cube.normals.push_back(Vec3::Unit(axis) * p[axis]);
  }
  return cube;
}

// Jets round a cube's edges off over a neighbourhood's radius (about two
// spacings); there the points take a neighbour's flat neighbourhood on their
// own face, and away from the edges nothing changes.
TEST(Normals, SharpenedNormalsKeepACubesEdges) {
  const PointSet cube = sample_cube(12000, 5);  // spacing about 0.045
  const JetFits fits = fit_jets(cube.points, 18, "cube");
  const std::vector<Vec3>& jets = fits.normals;
  std::size_t replaced = 0;
  const std::vector<Vec3> normals = sharpen_normals(cube.points, fits, 18, &replaced);
  EXPECT_GT(replaced, 1000u);
  double band_before = 0, band_after = 0, far_worst = 0;
  std::size_t band = 0;
  for (std::size_t i = 0; i < cube.size(); ++i) {
    EXPECT_GE(normals[i].dot(jets[i]), 0) << i;  // the signs are kept
    // The distance to the nearest edge of the point's own face.
    const Vec3& p = cube.points[i];
    double edge = 2;
    for (int a = 0; a < 3; ++a)
      if (std::abs(p[a]) < 1) edge = std::min(edge, 1 - std::abs(p[a]));
    const double before = degrees_between_lines(jets[i], cube.normals[i]);
    const double after = degrees_between_lines(normals[i], cube.normals[i]);
    if (edge >= 0.025 && edge < 0.1) {  // half a spacing to two from the edge
      ++band;
      band_before += before;
      band_after += after;
    } else if (edge >= 0.2) {
      far_worst = std::max(far_worst, after);
    }
  }
  ASSERT_GT(band, 1000u);
  EXPECT_GT(band_before / band, 8.0);  // the jets' rounding
  EXPECT_LT(band_after / band, 2.0);
  EXPECT_LT(far_worst, 0.5);
}

TEST(Normals, MstOrientsEveryNormalOfASphereOneWay) {
  const PointSet sphere = test::sample_sphere(2000);
  std::vector<Vec3> normals = sphere.normals;
  flip_random_normals(normals, 0.5, 7);
  std::size_t unreached = 1;
  const std::size_t flipped = orient_normals_mst(sphere.points, normals, 18, &unreached);
  EXPECT_EQ(unreached, 0u);
  EXPECT_GT(flipped, 500u);
  // All outward (the top point faces +z) or, would the seed be wrong, all inward.
  int outward = 0;
  for (std::size_t i = 0; i < normals.size(); ++i) outward += normals[i].dot(sphere.normals[i]) > 0;
  EXPECT_EQ(outward, static_cast<int>(normals.size()));
}

TEST(Normals, ZeroNormalsAreFilledFromTheirNeighbours) {
  PointSet sphere = test::sample_sphere(3000);
  const std::vector<Vec3> truth = sphere.normals;
  for (std::size_t i = 0; i < sphere.size(); i += 300) sphere.normals[i] = Vec3::Zero();
  std::vector<Vec3> normals = sphere.normals;
  EXPECT_EQ(fill_missing_normals(sphere.points, normals, 18, "s"), 10u);
  for (std::size_t i = 0; i < sphere.size(); ++i)
    EXPECT_GT(normals[i].dot(truth[i]), std::cos(2 * M_PI / 180)) << i;  // within 2 degrees
  // A reconstruction keeps the given normals and fills the zero ones, and says so.
  ReconstructOptions o;
  o.target_edge_length = 0.12;
  const Result r = reconstruct(sphere, o);
  EXPECT_EQ(r.normals.filled, 10u);
  EXPECT_FALSE(r.normals.oriented);
  EXPECT_NE(normals_note(r).find("10 zero normals replaced"), std::string::npos);
  EXPECT_TRUE(surface_topology(r.mesh).closed);
  EXPECT_EQ(surface_topology(r.mesh).components, 1u);
}

TEST(Normals, APatchOfZeroNormalsTakesTheSignOfTheNearestGivenOnes) {
  // A cap of zero normals: inside it the nearest points give no sign.
  PointSet sphere = test::sample_sphere(3000);
  const std::vector<Vec3> truth = sphere.normals;
  std::size_t cap = 0;
  for (std::size_t i = 0; i < sphere.size(); ++i)
    if (sphere.points[i].z() > 0.7) {
      sphere.normals[i] = Vec3::Zero();
      ++cap;
    }
  ASSERT_GT(cap, 300u);
  std::vector<Vec3> normals = sphere.normals;
  EXPECT_EQ(fill_missing_normals(sphere.points, normals, 18, "s"), cap);
  for (std::size_t i = 0; i < sphere.size(); ++i)
    EXPECT_GT(normals[i].dot(truth[i]), std::cos(2 * M_PI / 180)) << i;
}

TEST(Normals, NormalsThatAreAllZeroAreEstimatedAndOriented) {
  PointSet sphere = test::sample_sphere(2000);
  for (Vec3& n : sphere.normals) n = Vec3::Zero();
  std::vector<Vec3> normals = sphere.normals;
  EXPECT_THROW(fill_missing_normals(sphere.points, normals, 18, "s"), std::invalid_argument);
  const Result r = reconstruct(sphere, bare_options(0.1, Orientation::kVisibility));
  EXPECT_TRUE(r.normals.estimated && r.normals.oriented);
  EXPECT_EQ(r.normals.filled, 0u);
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  for (const Vec3& v : r.mesh.vertices) EXPECT_NEAR(v.norm(), 1.0, 0.02);
}

TEST(Normals, TooFewPointsAreAnInputErrorNamingTheSource) {
  const PointSet few = without_normals(test::sample_sphere(10));
  ReconstructOptions o = bare_options(0.3);
  o.source = "few.xyz";
  try {
    reconstruct(few, o);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("few.xyz: 10 points are too few to estimate normals"),
              std::string::npos)
        << e.what();
  }
}

TEST(Normals, NoiseGrowsTheNeighbourhood) {
  EXPECT_EQ(noise_scaled_neighbors(0, 0.01, 18), 18);
  EXPECT_EQ(noise_scaled_neighbors(0.0005, 0.01, 18), 18);  // clean: as given
  EXPECT_EQ(noise_scaled_neighbors(0.005, 0.01, 18), 72);   // 18 x (0.005 / 0.0025)^2
  EXPECT_EQ(noise_scaled_neighbors(0.05, 0.01, 18), kMaxNoiseNeighbors);
}

TEST(Normals, PointsOffTheSurfaceJoinTheirNeighboursSegment) {
  // A few points a spacing off the sphere fail every link's tangent test;
  // alone, each would be turned by its own vote.
  PointSet sphere = test::sample_sphere(2000);
  for (int i = 0; i < 2000; i += 400) sphere.points[i] *= 1.08;
  std::vector<Vec3> normals = sphere.normals;
  flip_random_normals(normals, 0.5, 5);
  const std::vector<int> segment = orient_segments(sphere.points, normals, 18);
  for (std::size_t i = 0; i < segment.size(); ++i) {
    EXPECT_EQ(segment[i], segment[0]) << i;
    EXPECT_GT(normals[i].dot(sphere.normals[i]) * normals[0].dot(sphere.normals[0]), 0) << i;
  }
}

class BareShape : public ::testing::TestWithParam<Orientation> {};

TEST_P(BareShape, SphereWithoutNormalsIsClosedAndClose) {
  const Result r = reconstruct(without_normals(test::sample_sphere(2000)),
                               bare_options(0.1, GetParam()));
  EXPECT_TRUE(r.normals.estimated && r.normals.oriented);
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  // Bounds from the Fibonacci spheres of 1800-2200 points: mean 0.0012-0.0013,
  // max 0.009-0.017 as the loop's path varies.
  double sum = 0;
  for (const Vec3& v : r.mesh.vertices) {
    EXPECT_NEAR(v.norm(), 1.0, 0.02);
    sum += std::abs(v.norm() - 1.0);
  }
  EXPECT_LT(sum / r.mesh.vertices.size(), 0.002);
}

// The torus (R 1, r 0.35) of 4000 points without normals: closed, genus one,
// every vertex within 0.02 of the truth.
Result expect_bare_torus(ReconstructOptions options) {
  const PointSet torus = test::sample_torus(4000, 1.0, 0.35);
  const Result r = reconstruct(without_normals(torus), options);
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 1);
  double worst = 0;
  for (const Vec3& v : r.mesh.vertices) worst = std::max(worst, test::distance_to_torus(v, 1.0, 0.35));
  EXPECT_LT(worst, 0.02);
  return r;
}

TEST_P(BareShape, TorusWithoutNormalsHasGenusOne) {
  expect_bare_torus(bare_options(0.08, GetParam()));
}

TEST_P(BareShape, ThinPlateWithoutNormalsKeepsBothSides) {
  // An ellipsoid ten times wider than thick: the two sides are close, where
  // a neighbourhood graph can jump across and flip one side. (Twenty times
  // thinner, its rim is sharper than the sampling and the tree flips a side:
  // docs/benchmarks.md, "Normals".)
  const Vec3 axes(1.0, 0.8, 0.1);
  const PointSet plate = test::sample_ellipsoid(6000, axes);
  const Result r = reconstruct(without_normals(plate), bare_options(0.03, GetParam()));
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  // About as close as with the true normals (the rim, sharper than the target edge, is the
  // farthest part of either).
  const Result truth = reconstruct(plate, bare_options(0.03));
  auto distances = [&axes](const TriangleMesh& mesh) {
    double mean = 0, worst = 0;
    for (const Vec3& v : mesh.vertices) {
      const double d = test::distance_to_ellipsoid(v, axes);
      mean += d;
      worst = std::max(worst, d);
    }
    return std::pair(mean / static_cast<double>(mesh.vertices.size()), worst);
  };
  const auto [mean, worst] = distances(r.mesh);
  const auto [truth_mean, truth_worst] = distances(truth.mesh);
  EXPECT_LT(mean, 1.2 * truth_mean);
  EXPECT_LT(worst, 2 * truth_worst);
}

TEST_P(BareShape, TwoNearbySpheresStayTwo) {
  PointSet both = test::sample_sphere(1500, 1.0, Vec3(0, 0, 0));
  const PointSet other = test::sample_sphere(1500, 1.0, Vec3(2.3, 0, 0));
  both.points.insert(both.points.end(), other.points.begin(), other.points.end());
  const Result r = reconstruct(without_normals(both), bare_options(0.1, GetParam()));
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 2);
  // Bounds from pairs of 1400-1600 points each: mean 0.0011, max 0.015-0.03
  // (a few vertices, as the loop's path varies).
  double sum = 0;
  for (const Vec3& v : r.mesh.vertices) {
    const double d = std::min((v - Vec3(0, 0, 0)).norm(), (v - Vec3(2.3, 0, 0)).norm());
    EXPECT_NEAR(d, 1.0, 0.035);
    sum += std::abs(d - 1.0);
  }
  EXPECT_LT(sum / r.mesh.vertices.size(), 0.002);
}

TEST_P(BareShape, FlippedNormalsReorientedGiveTheTrueNormalsSurface) {
  const PointSet sphere = test::sample_sphere(2000);
  const Result truth = reconstruct(sphere, bare_options(0.1));
  for (const double fraction : {1.0, 0.5}) {
    PointSet flipped = sphere;
    flip_random_normals(flipped.normals, fraction, 3);
    ReconstructOptions o = bare_options(0.1, GetParam());
    o.normals = NormalsMode::kOrient;
    const Result r = reconstruct(flipped, o);
    EXPECT_FALSE(r.normals.estimated);
    EXPECT_GT(r.normals.flipped, 500u);
    // The signs come back exactly, so the run is the true normals' run.
    EXPECT_EQ(r.mesh.vertices, truth.mesh.vertices) << "fraction " << fraction;
    EXPECT_EQ(r.mesh.faces, truth.mesh.faces) << "fraction " << fraction;
  }
}

TEST_P(BareShape, NoisyTorusWithoutNormalsIsOrientedAndHasGenusOne) {
  // Noise 0.04 against a spacing of about 0.06: jets over 18 neighbours are
  // off by 14 degrees on average and link the two sides of the noise band.
  PointSet torus = test::sample_torus(4000, 1.0, 0.35);
  test::add_noise(torus, 0.04, 11);
  const ReconstructOptions options = bare_options(0.08, GetParam());
  NormalsReport report;
  const PointSet prepared = prepare_normals(without_normals(torus), options, &report);
  EXPECT_TRUE(report.smoothed);
  EXPECT_GT(report.neighbors, 40);
  double mean = 0;
  for (std::size_t i = 0; i < prepared.size(); ++i) {
    const Vec3& p = prepared.points[i];
    const Vec3 truth = (p - Vec3(p.x(), p.y(), 0).normalized()).normalized();
    const double angle = std::acos(std::clamp(prepared.normals[i].dot(truth), -1.0, 1.0)) * 180 / M_PI;
    EXPECT_LT(angle, 30) << i;  // outward, and close
    mean += angle / static_cast<double>(prepared.size());
  }
  EXPECT_LT(mean, 5);
  const Result r = reconstruct(without_normals(torus), options);
  const SurfaceTopology t = surface_topology(r.mesh);
  EXPECT_TRUE(t.closed && t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 1);
  double distance = 0;
  for (const Vec3& v : r.mesh.vertices)
    distance += test::distance_to_torus(v, 1.0, 0.35) / static_cast<double>(r.mesh.vertices.size());
  EXPECT_LT(distance, 0.01);
}

// A scan of a house without its floor (the scanner never saw it): four walls
// and a flat roof of a 2 x 1.2 x 1 box, points on a jittered grid, their
// normals outward. Inside and outside meet through the open base, so no
// solve encloses an inside; the roof is seen from the sky, the walls from
// around.
PointSet open_house(double spacing) {
  PointSet house;
  const Vec3 size(2.0, 1.2, 1.0);
  std::uint64_t state = 12345;
  const auto jitter = [&state, spacing] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.5 * spacing;
  };
  // Face: axis a fixed at 0 or size[a] (side -1 or +1), spanning the other two.
  const auto face = [&](int a, int side) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (double u = spacing / 2; u < size[b]; u += spacing)
      for (double v = spacing / 2; v < size[c]; v += spacing) {
        Vec3 p;
        p[a] = side > 0 ? size[a] : 0;
        p[b] = std::clamp(u + jitter(), 0.0, size[b]);
        p[c] = std::clamp(v + jitter(), 0.0, size[c]);
        Vec3 n = Vec3::Zero();
        n[a] = side;
        house.points.push_back(p);
        house.normals.push_back(n);
      }
  };
  face(0, -1), face(0, 1), face(1, -1), face(1, 1), face(2, 1);  // no floor (z = 0)
  return house;
}

TEST(Normals, VisibilityTurnsAnOpenScanOutward) {
  const PointSet house = open_house(0.04);
  ReconstructOptions options;
  options.orientation = Orientation::kVisibility;
  NormalsReport report;
  const PointSet prepared = prepare_normals(without_normals(house), options, &report);
  ASSERT_EQ(prepared.size(), house.size());
  EXPECT_EQ(report.orientation, Orientation::kVisibility);
  std::size_t outward = 0;
  for (std::size_t i = 0; i < house.size(); ++i)
    outward += prepared.normals[i].dot(house.normals[i]) > 0;
  // All but a few at the edges, where jets round the corner.
  EXPECT_GT(static_cast<double>(outward), 0.99 * static_cast<double>(house.size()));
}

TEST(Normals, AOneSidedScanIsUnclearToVisibilityAndTakesTheSpectralVote) {
  // A cap of the unit sphere 50 degrees around its pole, as one view sees
  // it: open on both sides, its rays escape either way.
  PointSet cap;
  for (const Vec3& p : test::sample_sphere(6000).points)
    if (p.z() > std::cos(50 * M_PI / 180)) cap.points.push_back(p);
  ReconstructOptions options;
  options.orientation = Orientation::kVisibility;
  NormalsReport report;
  const PointSet prepared = prepare_normals(cap, options, &report);
  EXPECT_EQ(report.unclear, cap.size());
  for (std::size_t i = 0; i < cap.size(); ++i)
    EXPECT_GT(prepared.normals[i].dot(cap.points[i]), 0.9) << i;  // outward, within 25 degrees
}

// The spectral solver needs normals but not their signs (Eq. 16): bare points
// get estimated normals and no orientation step.
TEST(Normals, TheSpectralSolverTakesEstimatedNormalsUnoriented) {
  ReconstructOptions o = bare_options(0.08);
  o.solver.kind = SolverKind::kSpectral;
  const Result r = expect_bare_torus(o);
  EXPECT_TRUE(r.normals.estimated);
  EXPECT_FALSE(r.normals.oriented);
  EXPECT_EQ(r.normals.segments, 0u);
}

INSTANTIATE_TEST_SUITE_P(Orientations, BareShape,
                         ::testing::Values(Orientation::kMst, Orientation::kSpectral,
                                           Orientation::kVisibility),
                         [](const auto& info) { return to_string(info.param); });

}  // namespace
}  // namespace pdd
