#include <pdd/errors.h>
#include <pdd/isofacet.h>
#include <pdd/pipeline.h>
#include <pdd/quality.h>
#include <pdd/refine.h>
#include <pdd/report.h>
#include <pdd/solvers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/shapes.h"

namespace pdd {
namespace {

// Small, fast settings: a coarse uniform target.
ReconstructOptions fast_options(SolverKind solver, double edge) {
  ReconstructOptions o;
  o.solver.kind = solver;
  o.target_edge_length = edge;
  return o;
}

struct Distances {
  double mean = 0, max = 0;
};

template <class Distance>
Distances vertex_distances(const TriangleMesh& mesh, Distance distance) {
  Distances d;
  for (const Vec3& v : mesh.vertices) {
    const double e = distance(v);
    d.mean += e;
    d.max = std::max(d.max, e);
  }
  d.mean /= static_cast<double>(mesh.vertices.size());
  return d;
}

void expect_closed_manifold(const TriangleMesh& mesh, long genus) {
  const SurfaceTopology topo = surface_topology(mesh);
  std::cout << "topology: non-manifold vertices " << topo.non_manifold_vertices << ", edges "
            << topo.non_manifold_edges << ", boundary edges " << topo.boundary_edges
            << ", components " << topo.components << ", degenerate " << topo.degenerate_faces
            << "\n";
  EXPECT_TRUE(topo.closed);
  EXPECT_TRUE(topo.manifold);
  EXPECT_EQ(topo.components, 1u);
  EXPECT_EQ(topo.genus, genus);
}

class SphereBySolver : public ::testing::TestWithParam<SolverKind> {};

TEST_P(SphereBySolver, ClosedManifoldAndCloseToTheTruth) {
  const PointSet input = test::sample_sphere(1500);
  const Result r = reconstruct(input, fast_options(GetParam(), 0.12));
  ASSERT_FALSE(r.cancelled);
  expect_closed_manifold(r.mesh, 0);
  const Distances d =
      vertex_distances(r.mesh, [](const Vec3& p) { return std::abs(p.norm() - 1.0); });
  std::cout << to_string(GetParam()) << ": " << r.mesh.faces.size() << " faces, "
            << r.iterations.size() << " iterations, mean " << d.mean << " max " << d.max << "\n";
  EXPECT_LT(d.mean, 0.01);
  // The largest deviations (3-4% over four samplings) sit in crossing tets
  // that reach the boundary sphere, only 0.4 away here: their long edges
  // carry a poor linear f, and §3.4's rules look at isofacet areas only.
  EXPECT_LT(d.max, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Solvers, SphereBySolver,
                         ::testing::Values(SolverKind::kSsd, SolverKind::kPoisson,
                                           SolverKind::kSpectral),
                         [](const auto& info) { return to_string(info.param); });

TEST(Pipeline, IsofacetsMeetTheUniformTarget) {
  // §3.4 with the optimizer between refinements: the loop stops once the
  // mean isofacet area is below the target and almost no facet calls for a
  // deterministic split; the mean then ends within 30% of the target (a pass
  // that splits a tet in 4 by the rules yields about 6 isofacets once the
  // Delaunay triangulation and the optimizer have reshaped it, so one pass
  // more would land near 0.6) and no facet is far above it.
  const PointSet input = test::sample_sphere(2000);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.1);
  const double target = area_for_edge_length(0.1);
  const Result r = reconstruct(input, o);
  const std::vector<Isofacet> facets = isofacets(r.domain.mesh(), r.domain.f());
  double mean = 0, largest = 0;
  for (const Isofacet& a : facets) {
    mean += a.area / static_cast<double>(facets.size());
    largest = std::max(largest, a.area);
  }
  std::cout << facets.size() << " isofacets, mean/target " << mean / target << ", max/target "
            << largest / target << "\n";
  EXPECT_GE(mean / target, 0.7);
  EXPECT_LE(mean / target, 1.3);
  EXPECT_LE(largest, 4 * target);
}

class TorusBySolver : public ::testing::TestWithParam<SolverKind> {};

TEST_P(TorusBySolver, HasGenusOneAndIsCloseToTheTruth) {
  const PointSet input = test::sample_torus(3000, 1.0, 0.35);
  const Result r = reconstruct(input, fast_options(GetParam(), 0.08));
  expect_closed_manifold(r.mesh, 1);
  const Distances d = vertex_distances(
      r.mesh, [](const Vec3& p) { return test::distance_to_torus(p, 1.0, 0.35); });
  const TriangleQuality q = triangle_quality(r.mesh);
  std::cout << to_string(GetParam()) << " torus: mean " << d.mean << " max " << d.max
            << ", mean min angle " << q.mean_min_angle << ", below 20: " << q.fraction_below_20
            << "\n";
  EXPECT_LT(d.mean, 0.01);
  EXPECT_GT(q.mean_min_angle, 35.0);
  EXPECT_LT(q.fraction_below_20, 0.02);  // issue 7's bound on real scans
}

INSTANTIATE_TEST_SUITE_P(Solvers, TorusBySolver,
                         ::testing::Values(SolverKind::kSsd, SolverKind::kPoisson,
                                           SolverKind::kSpectral),
                         [](const auto& info) { return to_string(info.param); });

// A plate two and a half target edges thick. Eq. (16) rewards |grad f| at
// the samples whatever its sign, so f may run through a thin part rather
// than around it; the tie of f over the domain's outer boundary keeps the
// outside one region. Measured: max distance 0.040 with the tie, 0.146
// without (outer_tie = 0); on bunny_clean an open sheet without it.
TEST(SpectralSolver, FollowsAThinPlate) {
  const Vec3 axes(1.0, 0.7, 0.15);
  const PointSet input = test::sample_ellipsoid(4000, axes);
  const Result r = reconstruct(input, fast_options(SolverKind::kSpectral, 0.06));
  expect_closed_manifold(r.mesh, 0);
  const Distances d =
      vertex_distances(r.mesh, [&](const Vec3& p) { return test::distance_to_ellipsoid(p, axes); });
  std::cout << "spectral plate: " << r.mesh.faces.size() << " faces, mean " << d.mean << " max "
            << d.max << ", value weight " << r.iterations.back().solver.value_weight << "\n";
  EXPECT_LT(d.mean, 0.004);
  EXPECT_LT(d.max, 0.07);
}

// Noise a fifth of the sample spacing (as in a dense scan): interpolated, as
// the noise alone would set alpha, the zero set follows it in bumps at the
// spacing; smoothed over 0.45 of a spacing (spectral_value_weight's floor) it
// lies nearer the truth. spacing = 0 turns the floor off.
TEST(SpectralSolver, SmoothsNoiseAtTheSampleSpacing) {
  PointSet input = test::sample_sphere(6000);
  test::add_noise(input, 0.006, 5);
  ReconstructOptions smoothed = fast_options(SolverKind::kSpectral, 0.05);
  ReconstructOptions interpolated = smoothed;
  interpolated.solver.spectral.spacing = 0;
  const auto distance = [](const Vec3& p) { return std::abs(p.norm() - 1.0); };
  const Result a = reconstruct(input, smoothed);
  const Result b = reconstruct(input, interpolated);
  expect_closed_manifold(a.mesh, 0);
  const Distances da = vertex_distances(a.mesh, distance);
  const Distances db = vertex_distances(b.mesh, distance);
  std::cout << "noisy sphere, spectral: smoothed alpha " << a.iterations.back().solver.value_weight
            << " mean " << da.mean << " max " << da.max << "; interpolated alpha "
            << b.iterations.back().solver.value_weight << " mean " << db.mean << " max "
            << db.max << "\n";
  EXPECT_LT(a.iterations.back().solver.value_weight, 0.3 * b.iterations.back().solver.value_weight);
  EXPECT_LT(da.mean, 0.8 * db.mean);
}

TEST(Pipeline, StatisticsAreConsistent) {
  const PointSet input = test::sample_sphere(1000);
  const Result r = reconstruct(input, fast_options(SolverKind::kSsd, 0.15));
  ASSERT_GE(r.iterations.size(), 2u);
  for (std::size_t i = 0; i < r.iterations.size(); ++i) {
    const IterationStats& s = r.iterations[i];
    EXPECT_EQ(s.iteration, static_cast<int>(i) + 1);
    EXPECT_GE(s.parsimony, 0.0);
    EXPECT_LE(s.parsimony, 1.0);
    EXPECT_LE(s.vertices_near_isosurface, s.vertices);
    EXPECT_GT(s.triangles, 0u);
  }
  const IterationStats& last = r.iterations.back();
  EXPECT_EQ(last.triangles, r.mesh.faces.size());
  EXPECT_EQ(last.isovertices, r.mesh.vertices.size());
  EXPECT_EQ(last.vertices, r.domain.num_vertices());
  // The domain grows while it refines.
  EXPECT_GT(r.iterations.back().vertices, r.iterations.front().vertices);
}

// Mean distance of the output's vertices to the unit sphere.
double sphere_error(const Result& r) {
  return vertex_distances(r.mesh, [](const Vec3& p) { return std::abs(p.norm() - 1.0); }).mean;
}

TEST(Pipeline, TheValueWeightFollowsTheNoiseAndBeatsAFixedOne) {
  // Clean samples: the noise estimate is about 0, alpha is at its cap, and
  // the surface lies closer to the truth than with PoissonRecon's weight
  // (4000 in our units).
  const PointSet clean = test::sample_sphere(6000);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.06);
  const Result automatic = reconstruct(clean, o);
  // Estimated on the points relative to their centre, where the run works.
  EXPECT_NEAR(automatic.noise, estimate_noise(clean), 1e-9 * estimate_noise(clean));
  for (const IterationStats& s : automatic.iterations)
    EXPECT_EQ(s.solver.value_weight, kSsdMaxValueWeight);
  o.solver.ssd.alpha = 4000;
  const Result fixed = reconstruct(clean, o);
  EXPECT_EQ(fixed.iterations.back().solver.value_weight, 4000);  // an explicit weight is kept
  EXPECT_EQ(fixed.noise, 0);            // and no estimate is made
  std::cout << "clean sphere: mean error " << sphere_error(automatic) << " (alpha "
            << automatic.iterations.back().solver.value_weight << ") against " << sphere_error(fixed) << " (4000)\n";
  // Measured 0.86 x: on a sphere most of the error is the linear elements'
  // own; on the shared data's bunny, whose details the smoother fit rounds
  // off, the cap halves it (docs/benchmarks.md, "The value weight").
  EXPECT_LT(sphere_error(automatic), 0.9 * sphere_error(fixed));

  // With noise of 1 % of the diameter the weight drops, and the surface lies
  // closer to the truth than with the clean inputs' weight (measured 0.17 x).
  PointSet noisy = clean;
  test::add_noise(noisy, 0.02, 3);
  o.solver.ssd.alpha = 0;
  const Result smoothed = reconstruct(noisy, o);
  const double alpha = smoothed.iterations.back().solver.value_weight;
  EXPECT_NEAR(smoothed.noise, estimate_noise(noisy), 1e-9 * estimate_noise(noisy));
  // l is about 2 (the noise widens the box a little)
  EXPECT_NEAR(alpha, ssd_value_weight(smoothed.noise, 2.0), 0.1 * alpha);
  EXPECT_LT(alpha, 0.1 * kSsdMaxValueWeight);
  o.solver.ssd.alpha = kSsdMaxValueWeight;
  const Result tight = reconstruct(noisy, o);
  std::cout << "noisy sphere: mean error " << sphere_error(smoothed) << " (alpha "
            << alpha << ") against " << sphere_error(tight) << " (the cap)\n";
  EXPECT_LT(sphere_error(smoothed), 0.8 * sphere_error(tight));

  // The screened Poisson solver takes its weight from the same estimate.
  o.solver.kind = SolverKind::kPoisson;
  const Result poisson = reconstruct(noisy, o);
  EXPECT_NEAR(poisson.noise, smoothed.noise, 1e-9 * smoothed.noise);
  EXPECT_NEAR(poisson.iterations.back().solver.value_weight, alpha, 0.1 * alpha);
}

TEST(Pipeline, PoissonsAutomaticScreeningBeatsPoissonRecons) {
  // PoissonRecon's weight (4) leaves a linear f's zero set ripple around a
  // clean sphere; the noise's weight (the cap here) pins it to the samples.
  // Measured: mean error 0.00055 automatic against 0.0015 with 4, and with
  // 1 % noise 0.0038 against the cap's 0.020 (docs/benchmarks.md, "Poisson's
  // screening").
  const PointSet clean = test::sample_sphere(6000);
  ReconstructOptions o = fast_options(SolverKind::kPoisson, 0.06);
  const Result automatic = reconstruct(clean, o);
  EXPECT_EQ(automatic.iterations.back().solver.value_weight, kSsdMaxValueWeight);
  o.solver.poisson.alpha = 4;
  const Result weak = reconstruct(clean, o);
  std::cout << "Poisson, clean sphere: mean error " << sphere_error(automatic)
            << " (automatic) against " << sphere_error(weak) << " (alpha 4)\n";
  EXPECT_LT(sphere_error(automatic), 0.5 * sphere_error(weak));

  PointSet noisy = clean;
  test::add_noise(noisy, 0.02, 3);
  o.solver.poisson.alpha = 0;
  const Result smoothed = reconstruct(noisy, o);
  o.solver.poisson.alpha = kSsdMaxValueWeight;
  const Result tight = reconstruct(noisy, o);
  std::cout << "Poisson, noisy sphere: mean error " << sphere_error(smoothed)
            << " (automatic) against " << sphere_error(tight) << " (the cap)\n";
  EXPECT_LT(sphere_error(smoothed), 0.8 * sphere_error(tight));
}

TEST(Pipeline, ABlobBelowTheResolutionIsRemovedAndCounted) {
  // A speck of 40 points beside the sphere: too small for the target edge to
  // resolve, it leaves a blob of a few triangles.
  PointSet input = test::sample_sphere(1000);
  const PointSet speck = test::sample_sphere(40, 0.04, Vec3(1.6, 0, 0));
  input.points.insert(input.points.end(), speck.points.begin(), speck.points.end());
  input.normals.insert(input.normals.end(), speck.normals.begin(), speck.normals.end());
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.15);
  o.cleanup = false;  // so that the two runs' faces differ by the blob's alone
  o.min_component_edges = 0;
  const Result all = reconstruct(input, o);
  ASSERT_EQ(surface_topology(all.mesh).components, 2u);
  EXPECT_EQ(all.iterations.back().small_components.components, 0);

  o.min_component_edges = 4;
  const Result r = reconstruct(input, o);
  expect_closed_manifold(r.mesh, 0);
  const IterationStats& last = r.iterations.back();
  EXPECT_EQ(last.small_components.components, 1);
  EXPECT_EQ(static_cast<std::size_t>(last.small_components.faces) + r.mesh.faces.size(),
            all.mesh.faces.size());
  EXPECT_EQ(last.triangles, r.mesh.faces.size());
  EXPECT_EQ(last.isovertices, r.mesh.vertices.size());
  for (const Vec3& v : r.mesh.vertices) EXPECT_LT(v.norm(), 1.2);
}

TEST(Pipeline, CancellingStopsCleanly) {
  const PointSet input = test::sample_sphere(800);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.15);
  int calls = 0;
  o.progress = [&](const Progress& p) {
    ++calls;
    return p.stage != "refine";
  };
  const Result r = reconstruct(input, o);
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.mesh.faces.empty());
  EXPECT_GT(calls, 1);
}

// Inside a stage the callback is asked again from the long loops (CG
// iterations, insertions): a false answer there stops the run in the middle
// of the stage, before its next report.
TEST(Pipeline, CancellingInsideASolveStopsBeforeItsEnd) {
  const PointSet input = test::sample_sphere(1500);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  o.progress_interval = 0;  // ask at every check, so that the test does not depend on time
  std::vector<std::pair<std::string, int>> stages;
  int solve_calls = 0;
  o.progress = [&](const Progress& p) {
    stages.emplace_back(p.stage, p.iteration);
    if (p.stage == "solve" && p.iteration == 2) ++solve_calls;
    return solve_calls < 3;  // the third call of the second solve: its CG has started
  };
  const Result r = reconstruct(input, o);
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.mesh.faces.empty());
  EXPECT_EQ(solve_calls, 3);
  EXPECT_EQ(stages.back(), std::make_pair(std::string("solve"), 2));
  // The first solve was contoured, the second was not.
  const auto contoured = [&](int iteration) {
    return std::count(stages.begin(), stages.end(),
                      std::make_pair(std::string("contour"), iteration));
  };
  EXPECT_GE(contoured(1), 1);
  EXPECT_EQ(contoured(2), 0);
}

// The default interval (0.1 s) keeps the calls inside a stage few.
TEST(Pipeline, CallsInsideAStageAreSpacedByTheInterval) {
  const PointSet input = test::sample_sphere(1500);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  int calls = 0;
  o.progress = [&](const Progress&) { return ++calls > 0; };
  o.progress_interval = 1e9;
  const Result spaced = reconstruct(input, o);
  const int per_stage = calls;
  calls = 0;
  o.progress_interval = 0;
  const Result every = reconstruct(input, o);
  EXPECT_EQ(spaced.mesh.faces, every.mesh.faces);  // asking changes nothing else
  EXPECT_GT(calls, 3 * per_stage);
}

// A size asked for as a triangle count: met within 15 % on a sphere, uniform
// or adaptive, and refused beside an edge length.
TEST(Pipeline, TargetFacesSetsTheOutputSize) {
  const PointSet input = test::sample_sphere(3000);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0);  // no target edge
  for (const int faces : {6000, 24000}) {
    o.target_faces = faces;
    const Result r = reconstruct(input, o);
    EXPECT_NEAR(static_cast<double>(r.mesh.faces.size()), faces, 0.15 * faces);
    expect_closed_manifold(r.mesh, 0);
  }
  o.sizing = SizingKind::kAdaptive;
  o.target_faces = 12000;
  EXPECT_NEAR(static_cast<double>(reconstruct(input, o).mesh.faces.size()), 12000, 0.15 * 12000);
  o.target_edge_length = 0.1;
  EXPECT_THROW(reconstruct(input, o), InputError);
}

// Spurious handles (issue 19): two spheres two target edges (and sample
// spacings) apart are not bridged, and a thin torus sparsely sampled (about 25
// samples around its tube) keeps genus 1 with the default sizing.
TEST(Pipeline, TwoSpheresAFewTargetEdgesApartStayTwo) {
  PointSet input = test::sample_sphere(3000);
  const ReconstructOptions o = fast_options(SolverKind::kSsd, 0.06);
  const double gap = 2 * o.target_edge_length;
  const PointSet other = test::sample_sphere(3000, 1.0, Vec3(2 + gap, 0, 0));
  input.points.insert(input.points.end(), other.points.begin(), other.points.end());
  input.normals.insert(input.normals.end(), other.normals.begin(), other.normals.end());
  const Result r = reconstruct(input, o);
  const SurfaceTopology topo = surface_topology(r.mesh);
  EXPECT_TRUE(topo.closed && topo.manifold);
  EXPECT_EQ(topo.components, 2u);
  EXPECT_EQ(topo.genus, 0);
  for (const Vec3& v : r.mesh.vertices)  // nothing in the middle of the gap
    EXPECT_GT(std::abs(v.x() - (1 + 0.5 * gap)), 0.25 * gap);
}

TEST(Pipeline, SparseThinTorusKeepsGenusOne) {
  const PointSet input = test::sample_torus(1000, 1.0, 0.12);
  const Result r = reconstruct(input, ReconstructOptions{});
  expect_closed_manifold(r.mesh, 1);
  const Distances d =
      vertex_distances(r.mesh, [](const Vec3& p) { return test::distance_to_torus(p, 1.0, 0.12); });
  EXPECT_LT(d.mean, 0.01);
}

// Adaptive sizing (§3.4) on a flat disc with a curved rim (an ellipsoid of
// axes 2, 2, 0.3), at the uniform default's triangle count (--target-faces):
// fewer of them on the flat part, counted, more on the rim, and a mean
// distance to the truth no larger. (Its largest distance is 2.5x the uniform
// one's: docs/benchmarks.md, "Adaptive sizing".)
TEST(Pipeline, AdaptiveSizingSpendsFewerTrianglesOnTheFlatPart) {
  const Vec3 axes(2, 2, 0.3);
  const PointSet input = test::sample_ellipsoid(6000, axes);
  auto flat = [](const TriangleMesh& m) {
    std::size_t count = 0;
    for (const auto& f : m.faces) {
      const Vec3 c = (m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]) / 3;
      count += std::hypot(c.x(), c.y()) < 1.0;
    }
    return count;
  };
  auto distances = [&](const TriangleMesh& m) {
    return vertex_distances(m, [&](const Vec3& p) { return test::distance_to_ellipsoid(p, axes); });
  };
  ReconstructOptions o;
  const Result uniform = reconstruct(input, o);
  o.sizing = SizingKind::kAdaptive;
  o.target_faces = static_cast<int>(uniform.mesh.faces.size());
  const Result adaptive = reconstruct(input, o);
  std::cout << "flat part: uniform " << flat(uniform.mesh) << " of " << uniform.mesh.faces.size()
            << " triangles, adaptive " << flat(adaptive.mesh) << " of "
            << adaptive.mesh.faces.size() << "; max distance uniform " << distances(uniform.mesh).max
            << ", adaptive " << distances(adaptive.mesh).max << "; mean "
            << distances(uniform.mesh).mean << ", " << distances(adaptive.mesh).mean << "\n";
  EXPECT_NEAR(static_cast<double>(adaptive.mesh.faces.size()), o.target_faces, 0.15 * o.target_faces);
  EXPECT_LT(flat(adaptive.mesh), flat(uniform.mesh) / 2);
  EXPECT_LT(distances(adaptive.mesh).mean, distances(uniform.mesh).mean);
}

TEST(Pipeline, SameSeedGivesIdenticalOutput) {
  const PointSet input = test::sample_ellipsoid(1200, Vec3(1.0, 0.7, 0.5));
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  o.seed = 42;
  const Result a = reconstruct(input, o);
  const Result b = reconstruct(input, o);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
}

TEST(Pipeline, OneThreadGivesTheSameOutputAsAll) {
  // Every parallel sum (TBB assembly, the multigrid's products and CG, here
  // on every domain of 500 vertices or more, Poisson's sample spacing) runs
  // in an order fixed by the mesh or the samples, for every solver.
  const PointSet input = test::sample_ellipsoid(1200, Vec3(1.0, 0.7, 0.5));
  for (SolverKind kind : {SolverKind::kSsd, SolverKind::kPoisson}) {
    ReconstructOptions o = fast_options(kind, 0.12);
    o.solver.linear.direct_below = 500;
    o.solver.linear.coarsest_size = 200;
    const Result all = reconstruct(input, o);
    o.threads = 1;
    const Result one = reconstruct(input, o);
    EXPECT_EQ(all.mesh.vertices, one.mesh.vertices) << to_string(kind);
    EXPECT_EQ(all.mesh.faces, one.mesh.faces) << to_string(kind);
  }
}

// Georeferenced coordinates: the run works relative to the input's centre,
// so a translated input gives the same mesh, translated, up to rounding; and
// the domain and the iterations come back in the input's coordinates.
TEST(Pipeline, ATranslatedInputGivesTheTranslatedMesh) {
  const PointSet input = test::sample_sphere(1500);
  const Vec3 shift(5e5, 5e6, 100);
  PointSet shifted = input;
  for (Vec3& p : shifted.points) p += shift;
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  const Result r = reconstruct(input, o);
  std::vector<Vec3> iteration_vertices;
  o.on_iteration = [&](const IterationStats&, const Domain& domain, const TriangleMesh& mesh) {
    iteration_vertices = mesh.vertices;
    EXPECT_NEAR((domain.center() - shift).norm(), 0, 1e-6);
  };
  const Result s = reconstruct(shifted, o);
  ASSERT_EQ(s.mesh.faces, r.mesh.faces);
  ASSERT_EQ(s.mesh.vertices.size(), r.mesh.vertices.size());
  double largest = 0;
  for (std::size_t i = 0; i < r.mesh.vertices.size(); ++i)
    largest = std::max(largest, (s.mesh.vertices[i] - shift - r.mesh.vertices[i]).norm());
  EXPECT_LT(largest, 1e-6);  // radius 1
  ASSERT_EQ(s.domain.num_vertices(), r.domain.num_vertices());
  for (std::size_t i = 0; i < r.domain.num_vertices(); ++i)
    EXPECT_LT((s.domain.vertices()[i] - shift - r.domain.vertices()[i]).norm(), 1e-6) << i;
  for (const Vec3& v : iteration_vertices) EXPECT_NEAR((v - shift).norm(), 1, 0.1);
  // The final solve freed the domain's triangulation (its peak of memory);
  // rebuilt when asked, it locates where the translated vertices are.
  EXPECT_TRUE(s.domain.triangulation_released());
  for (std::size_t i = 0; i < input.size(); i += 10)
    EXPECT_NEAR(s.domain.interpolate(shifted.points[i], s.domain.f()),
                r.domain.interpolate(input.points[i], r.domain.f()), 1e-6);
  EXPECT_FALSE(s.domain.triangulation_released());
}

TEST(Pipeline, OtherDomainStrategiesReconstructTheSphere) {
  const PointSet input = test::sample_sphere(1000);
  for (DomainStrategy s :
       {DomainStrategy::kDirect, DomainStrategy::kInput, DomainStrategy::kOctree}) {
    ReconstructOptions o = fast_options(SolverKind::kSsd, 0.15);
    o.strategy = s;
    const Result r = reconstruct(input, o);
    const SurfaceTopology topo = surface_topology(r.mesh);
    EXPECT_TRUE(topo.closed) << to_string(s);
    const Distances d =
        vertex_distances(r.mesh, [](const Vec3& p) { return std::abs(p.norm() - 1.0); });
    EXPECT_LT(d.mean, 0.02) << to_string(s);
  }
}

TEST(Pipeline, MultigridAndCholmodGiveTheSameSurface) {
  // Multigrid CG on every domain of 500 vertices or more, its levels from the
  // earlier domains, against CHOLMOD on every domain: the same mesh up to the
  // CG tolerance (the same face count within 2 %, the same deviation).
  const PointSet input = test::sample_sphere(1500);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  o.solver.linear.direct_below = 500;
  o.solver.linear.coarsest_size = 200;
  const Result mg = reconstruct(input, o);
  ASSERT_GE(mg.iterations.size(), 3u);
  EXPECT_EQ(mg.iterations.front().solver.method, "cholmod");
  int multigrid_solves = 0;
  for (const IterationStats& s : mg.iterations) {
    if (s.solver.method != "cg+multigrid") continue;
    ++multigrid_solves;
    EXPECT_GE(s.solver.levels, 2) << "iteration " << s.iteration;
    EXPECT_LE(s.solver.residual, 1e-6) << "iteration " << s.iteration;
  }
  EXPECT_GE(multigrid_solves, 2);

  o.solver.linear.method = LinearMethod::kCholmod;
  const Result direct = reconstruct(input, o);
  for (const IterationStats& s : direct.iterations) EXPECT_EQ(s.solver.method, "cholmod");
  auto deviation = [](const Vec3& p) { return std::abs(p.norm() - 1.0); };
  const Distances d_mg = vertex_distances(mg.mesh, deviation);
  const Distances d_direct = vertex_distances(direct.mesh, deviation);
  std::cout << "mean deviation: multigrid " << d_mg.mean << ", cholmod " << d_direct.mean
            << "; faces " << mg.mesh.faces.size() << " / " << direct.mesh.faces.size() << "\n";
  EXPECT_NEAR(d_mg.mean, d_direct.mean, 0.05 * d_direct.mean + 1e-5);
  EXPECT_NEAR(static_cast<double>(mg.mesh.faces.size()),
              static_cast<double>(direct.mesh.faces.size()), 0.02 * direct.mesh.faces.size());
}

TEST(Pipeline, ABudgetTooSmallForTheTargetCoarsensTheSizing) {
  // A unit sphere at edge 0.02 needs a domain of about 36k vertices; 200 MB
  // allow about 25k: the run coarsens its sizing, says so, stays within the
  // vertex budget and still gives a closed sphere.
  const PointSet input = test::sample_sphere(3000);
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.02);
  o.max_memory = parse_memory_size("200M");
  const Result r = reconstruct(input, o);
  EXPECT_EQ(r.budget.bytes, 200u << 20);
  EXPECT_GT(r.budget.coarsening, 1.0);
  EXPECT_GT(r.budget.predicted_vertices, r.budget.vertices);
  EXPECT_LE(r.domain.num_vertices(), r.budget.vertices);
  EXPECT_NE(memory_budget_note(r).find("coarsened"), std::string::npos) << memory_budget_note(r);
  expect_closed_manifold(r.mesh, 0);
  const Distances d =
      vertex_distances(r.mesh, [](const Vec3& p) { return std::abs(p.norm() - 1.0); });
  EXPECT_LT(d.mean, 0.01);

  o.max_memory = 0;  // the default budget: no coarsening on this machine's free memory
  const Result full = reconstruct(input, o);
  EXPECT_EQ(full.budget.coarsening, 1.0);
  EXPECT_EQ(memory_budget_note(full), "");
  EXPECT_GT(full.domain.num_vertices(), r.domain.num_vertices());

  EXPECT_THROW(parse_memory_size("12 parsecs"), InputError);
  EXPECT_EQ(parse_memory_size("1.5GiB"), std::size_t{3} << 29);
  o.max_memory = 1 << 20;
  EXPECT_THROW(reconstruct(input, o), InputError);
}

TEST(Pipeline, EverySolveButTheFirstRunsOnAnOptimizedRefinedDomain) {
  // Optimizer passes on both sides of the refiner: each iteration after the
  // first optimizes its refined domain and then solves on it, and the last
  // of these solves is the final one (no second solve on the same domain).
  const PointSet input = test::sample_sphere(1000);
  const Result r = reconstruct(input, fast_options(SolverKind::kSsd, 0.15));
  ASSERT_GE(r.iterations.size(), 3u);
  EXPECT_EQ(r.iterations.front().solver.method, "cholmod");
  for (std::size_t i = 1; i < r.iterations.size(); ++i) {
    const IterationStats& s = r.iterations[i];
    EXPECT_GT(s.vertices, r.iterations[i - 1].vertices) << "iteration " << s.iteration;
    EXPECT_GT(s.optimizer_cg_iterations, 0) << "iteration " << s.iteration;
    EXPECT_GT(r.iterations[i - 1].inserted_points, 0) << "iteration " << s.iteration - 1;
  }
  EXPECT_EQ(r.iterations.back().inserted_points, 0);
}

// The isofacets against the sizing field as an iteration recorded them.
IsofacetAreaStats measured_sizing(const IterationStats& s) {
  IsofacetAreaStats a;
  a.count = s.crossing_tets;
  a.mean_ratio = s.mean_area_ratio;
  a.above_4 = s.above_4;
  a.away = s.away_from_data;
  a.above_4_away = s.above_4_away_from_data;
  return a;
}

TEST(Pipeline, TheStatisticsShowWhyTheLoopRefinedAndWhyItStopped) {
  // Each iteration records its isofacets against the sizing field: every one
  // that was refined had not met it (mean area ratio over 1, or too many
  // facets at 4x their target), and the last met it or followed a refinement
  // that split under 2 % of the crossing tets.
  const PointSet input = test::sample_sphere(1000);
  const ReconstructOptions o = fast_options(SolverKind::kSsd, 0.15);
  const Result r = reconstruct(input, o);
  ASSERT_GE(r.iterations.size(), 3u);
  const auto met = [](const IterationStats& s) { return sizing_met(measured_sizing(s)); };
  for (std::size_t i = 0; i + 1 < r.iterations.size(); ++i) {
    const IterationStats& s = r.iterations[i];
    EXPECT_GT(s.crossing_tets, 0) << "iteration " << s.iteration;
    EXPECT_FALSE(met(s)) << "iteration " << s.iteration << ": mean ratio " << s.mean_area_ratio;
    EXPECT_GT(s.trisected + s.bisected, 0) << "iteration " << s.iteration;
  }
  const IterationStats& last = r.iterations.back();
  const IterationStats& before = r.iterations[r.iterations.size() - 2];
  EXPECT_GT(last.crossing_tets, before.crossing_tets);
  EXPECT_GT(last.mean_area_ratio, 0.0);
  EXPECT_LT(last.mean_area_ratio, before.mean_area_ratio);
  EXPECT_TRUE(met(last) || before.trisected + before.bisected <
                               0.03 * static_cast<double>(before.crossing_tets))
      << "mean ratio " << last.mean_area_ratio << ", " << last.above_4 << " of "
      << last.crossing_tets << " at 4x their target";
}

TEST(Pipeline, RejectsBadOptions) {
  const PointSet input = test::sample_sphere(100);
  ReconstructOptions o;
  o.max_iterations = 0;
  EXPECT_THROW(reconstruct(input, o), InputError);
  o = ReconstructOptions();
  o.solver.linear.cg_tolerance = 0;
  EXPECT_THROW(reconstruct(input, o), InputError);
  o = ReconstructOptions();
  o.solver.linear.coarsening_ratio = 1;
  EXPECT_THROW(reconstruct(input, o), InputError);
  o = ReconstructOptions();
  o.optimizer_rounds_before_refining = -1;
  EXPECT_THROW(reconstruct(input, o), InputError);
  o = ReconstructOptions();
  o.min_component_edges = -1;
  EXPECT_THROW(reconstruct(input, o), InputError);
  EXPECT_THROW(parse_domain_strategy("quadtree"), InputError);
  EXPECT_THROW(parse_sizing_kind("curvy"), InputError);
}

}  // namespace
}  // namespace pdd

namespace pdd {
namespace {

TEST(Pipeline, TheDefaultSizingStaysInProportionToTheInput) {
  // 40 points on a sphere: the default target (0.7 % of the diagonal) would give
  // about 30k vertices; the run keeps to 60 triangles per point plus 5000.
  const PointSet few = test::sample_sphere(40);
  const Result r = reconstruct(few);
  EXPECT_TRUE(r.budget.limited_by_input);
  EXPECT_GT(r.budget.coarsening, 2);
  EXPECT_LT(r.mesh.faces.size(), 1.2 * (60 * 40 + 5000));
  EXPECT_TRUE(surface_topology(r.mesh).closed);
  EXPECT_NE(memory_budget_note(r).find("out of proportion to the input"), std::string::npos);

  // A sizing the user asks for is theirs.
  ReconstructOptions asked;
  asked.target_edge_length = 0.05;
  const Result fine = reconstruct(few, asked);
  EXPECT_EQ(fine.budget.input_vertices, 0u);
  EXPECT_FALSE(fine.budget.limited_by_input);
  EXPECT_GT(fine.mesh.faces.size(), 2 * r.mesh.faces.size());
}

TEST(Pipeline, UniformOutliersAreDroppedCountedAndLeaveOneSurface) {
  // 2 % of points uniform in the sphere's enlarged bounding box, with random normals.
  PointSet input = test::sample_sphere(2000);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  const int strays = 40;
  for (int i = 0; i < strays; ++i) {
    input.points.emplace_back(u(rng), u(rng), u(rng));
    input.normals.push_back(Vec3(u(rng), u(rng), u(rng)).normalized());
  }
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.1);
  const Result r = reconstruct(input, o);
  expect_closed_manifold(r.mesh, 0);
  // The test finds the strays well away from the surface (here, with 16 neighbours about
  // 0.16 apart, those more than 0.6 off); those nearer leave blobs that the removal of
  // unsupported components takes.
  std::size_t far = 0;
  for (int i = 0; i < strays; ++i) far += std::abs(input.points[2000 + i].norm() - 1) > 0.6;
  std::cout << r.outliers.removed << " of " << strays << " strays dropped, " << far
            << " far ones\n";
  EXPECT_GE(r.outliers.removed, far);
  EXPECT_GT(far, 0u);
  EXPECT_LE(r.outliers.removed, static_cast<std::size_t>(strays));
  const std::string json = statistics_json(r, o);
  EXPECT_NE(json.find("\"removed\": " + std::to_string(r.outliers.removed)), std::string::npos);
  EXPECT_NE(outliers_note(r).find(std::to_string(r.outliers.removed) + " outliers"),
            std::string::npos);
  // Without the test the strays leave more than one component.
  o.outliers.ratio = 0;
  o.min_component_samples = 0;
  const Result kept = reconstruct(input, o);
  EXPECT_EQ(kept.outliers.removed, 0u);
  EXPECT_GT(surface_topology(kept.mesh).components, 1u);
}

// The points of a 3000-point sampling of the unit sphere above z = 0, with their normals.
PointSet upper_hemisphere() {
  PointSet input;
  const PointSet sphere = test::sample_sphere(3000);
  for (std::size_t i = 0; i < sphere.size(); ++i)
    if (sphere.points[i].z() > 0) {
      input.points.push_back(sphere.points[i]);
      input.normals.push_back(sphere.normals[i]);
    }
  return input;
}

TEST(Pipeline, ATrimmedHemisphereIsOneOpenPieceNearTheSamples) {
  const PointSet input = upper_hemisphere();
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.08);
  o.trim.distance = 2;
  const Result r = reconstruct(input, o);
  ASSERT_TRUE(r.trim.trimmed);
  const SurfaceTopology topo = surface_topology(r.mesh);
  EXPECT_TRUE(topo.manifold);
  EXPECT_FALSE(topo.closed);
  EXPECT_EQ(topo.components, 1u);
  EXPECT_EQ(r.trim.boundary_loops, 1);
  EXPECT_GT(r.trim.area_removed, 0.3);
  for (const Vec3& v : r.mesh.vertices) {
    EXPECT_GT(v.z(), -5 * r.trim.spacing);
    EXPECT_LT(std::abs(v.norm() - 1), 0.05);
  }
  // The cut keeps the mesh's quality: about that of the closed run.
  const TriangleQuality q = triangle_quality(r.mesh);
  o.trim.distance = 0;
  const TriangleQuality closed = triangle_quality(reconstruct(input, o).mesh);
  std::cout << "under 20 degrees: closed " << closed.fraction_below_20 << ", trimmed "
            << q.fraction_below_20 << "; mean min angle " << closed.mean_min_angle << ", "
            << q.mean_min_angle << "\n";
  EXPECT_LT(q.fraction_below_20, closed.fraction_below_20 + 0.01);
  EXPECT_GT(q.mean_min_angle, closed.mean_min_angle - 1.5);
  EXPECT_EQ(r.iterations.back().triangles, r.mesh.faces.size());
  // The trim's rim is counted, but is no surprise to report.
  EXPECT_EQ(r.iterations.back().boundary_edges, surface_topology(r.mesh).boundary_edges);
  EXPECT_EQ(open_surface_note(r), "");
}

TEST(Pipeline, TheLargeFacetsAwayFromTheDataDoNotKeepTheLoopGoing) {
  // The closed run of a hemisphere invents its lower half: there the targets
  // are coarsened, the facets counted apart, and their 4x tail ignored by the
  // stop (refine.h, sizing_met).
  const PointSet input = upper_hemisphere();
  const Result r = reconstruct(input, fast_options(SolverKind::kSsd, 0.08));
  const double band = 12 * average_spacing(input);
  for (const IterationStats& s : r.iterations) {
    EXPECT_LE(s.away_from_data, s.crossing_tets) << "iteration " << s.iteration;
    EXPECT_LE(s.above_4_away_from_data, std::min(s.above_4, s.away_from_data))
        << "iteration " << s.iteration;
  }
  const IterationStats& last = r.iterations.back();
  // The output's vertices more than a band below the rim are away.
  std::size_t below = 0;
  for (const Vec3& v : r.mesh.vertices) below += v.z() < -1.2 * band;
  ASSERT_GT(below, 0u);
  EXPECT_GT(last.away_from_data, 0);
  EXPECT_LT(last.away_from_data, last.crossing_tets / 2);
  const IterationStats& before = r.iterations[r.iterations.size() - 2];
  EXPECT_TRUE(sizing_met(measured_sizing(last)) || before.trisected + before.bisected <
                                   0.03 * static_cast<double>(before.crossing_tets));
}

TEST(Pipeline, AnOpenSheetThatReachesTheDomainsBoundaryIsReported) {
  // A shallow cap sampled on one side only, its normals up: the zero set runs
  // on to the domain's boundary sphere, and the output is open there.
  PointSet sheet;
  const int n = 40;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1 + 2.0 * (i + 0.5) / n, y = -1 + 2.0 * (j + 0.5) / n;
      sheet.points.emplace_back(x, y, 0.1 * (x * x + y * y));
      sheet.normals.push_back(Vec3(-0.2 * x, -0.2 * y, 1).normalized());
    }
  const Result r = reconstruct(sheet, fast_options(SolverKind::kSsd, 0.1));
  const std::size_t edges = surface_topology(r.mesh).boundary_edges;
  EXPECT_GT(edges, 0u);
  EXPECT_EQ(r.iterations.back().boundary_edges, edges);
  EXPECT_NE(open_surface_note(r).find("the output is open (" + std::to_string(edges) +
                                      " boundary edges)"),
            std::string::npos)
      << open_surface_note(r);
  // A closed surface has none, and no note.
  const Result sphere = reconstruct(test::sample_sphere(1500), fast_options(SolverKind::kSsd, 0.15));
  EXPECT_EQ(sphere.iterations.back().boundary_edges, 0u);
  EXPECT_EQ(open_surface_note(sphere), "");
}

// Pairs of points on the sphere far below a scanned hemisphere's rim: the
// outlier test drops them from the solve, but the closed surface passes
// through them, and the trim keeps it there (the points to surface distance
// of a trimmed run is that of the closed run; issue 16).
TEST(Pipeline, TheTrimKeepsTheSurfaceThroughPointsTheOutlierTestDropped) {
  PointSet input = upper_hemisphere();
  std::vector<Vec3> pairs;
  for (int k = 0; k < 4; ++k)
    for (const double da : {0.0, 0.05}) {
      const double a = k * M_PI / 2 + da;
      pairs.push_back(Vec3(std::cos(a), std::sin(a), -0.5).normalized());
      input.points.push_back(pairs.back());
      input.normals.push_back(pairs.back());
    }
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.08);
  const Result closed = reconstruct(input, o);
  o.trim.distance = 2;
  const Result trimmed = reconstruct(input, o);
  EXPECT_GE(trimmed.outliers.removed, 4u);
  auto to_vertices = [](const TriangleMesh& mesh, const Vec3& p) {
    double nearest = 1e9;
    for (const Vec3& v : mesh.vertices) nearest = std::min(nearest, (v - p).norm());
    return nearest;
  };
  int through = 0;
  for (const Vec3& p : pairs) {
    const double before = to_vertices(closed.mesh, p), after = to_vertices(trimmed.mesh, p);
    std::cout << "closed " << before << ", trimmed " << after << "\n";
    if (before > trimmed.trim.spacing) continue;  // the closed surface misses it
    ++through;
    EXPECT_LT(after, before + 0.08);  // within an edge of where it was
  }
  EXPECT_GT(through, 0);
}

TEST(Pipeline, ColoursOfTheSamplesReachTheOutputVertices) {
  PointSet input = test::sample_sphere(2000);
  Attribute red{"red", "uchar", {}}, green{"green", "uchar", {}}, blue{"blue", "uchar", {}},
      label{"segment_index", "int", {}};
  for (const Vec3& p : input.points) {
    red.values.push_back(std::round(127.5 * (p.z() + 1)));
    green.values.push_back(0);
    blue.values.push_back(255);
    label.values.push_back(p.x() > 0);
  }
  input.attributes = {red, green, blue, label};
  ReconstructOptions o = fast_options(SolverKind::kSsd, 0.12);
  const Result r = reconstruct(input, o);
  ASSERT_EQ(r.mesh.attributes.size(), 3u);  // colours by default, not the label
  double error = 0;
  for (std::size_t v = 0; v < r.mesh.vertices.size(); ++v)
    error += std::abs(r.mesh.attributes[0].values[v] - 127.5 * (r.mesh.vertices[v].z() + 1));
  error /= static_cast<double>(r.mesh.vertices.size());
  std::cout << "mean red error " << error << " of 255\n";
  EXPECT_LT(error, 3);
  o.attributes = "segment_index";
  EXPECT_EQ(reconstruct(input, o).mesh.attributes.size(), 1u);
  o.attributes = "intensity";
  EXPECT_THROW(reconstruct(input, o), InputError);
  EXPECT_THROW(parse_attribute_selection("red,,blue"), InputError);
}

}  // namespace
}  // namespace pdd
