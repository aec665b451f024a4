// The three implicit solvers of §3.5 on analytic shapes: the zero set of f,
// contoured by marching tetrahedra, must lie close to the true surface, get
// closer when the domain is refined, survive noise (Poisson, SSD) and
// flipped normals (spectral), and f must be negative inside.
//
// Tolerances are in the shapes' units (sphere of radius 1, ellipsoid
// (1, 0.7, 0.5), torus (1, 0.4)); h is the spacing of the domain near the
// surface. Measured values, for reference, are printed by each test.
#include <pdd/contour.h>
#include <pdd/domain.h>
#include <pdd/errors.h>
#include <pdd/optimize.h>
#include <pdd/refine.h>
#include <pdd/sizing.h>
#include <pdd/solvers.h>

#include "support/shapes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <random>

namespace pdd {
namespace {

using Distance = std::function<double(const Vec3&)>;  // signed: < 0 inside

// A domain that is "fine enough" near the surface: the initial domain of §3.2
// plus a jittered lattice of spacing h in the shell |d| < 3h around the
// surface and of spacing 3h elsewhere.
Domain shell_domain(const PointSet& samples, const Distance& signed_distance, double h,
                    unsigned seed = 1) {
  Domain domain = Domain::initial(samples);
  const Vec3 c = domain.center();
  const double keep = 0.85 * domain.radius();  // safely inside the domain's hull
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.25 * h, 0.25 * h);
  std::vector<Vec3> extra;
  const int n = static_cast<int>(std::ceil(keep / h));
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        const Vec3 p = c + h * Vec3(i, j, k) + Vec3(jitter(rng), jitter(rng), jitter(rng));
        if ((p - c).norm() > keep) continue;
        const bool coarse = i % 3 == 0 && j % 3 == 0 && k % 3 == 0;
        if (coarse || std::abs(signed_distance(p)) < 3 * h) extra.push_back(p);
      }
  domain.insert(extra);
  return domain;
}

struct ZeroSetError {
  double max = 0;
  double mean = 0;
  std::size_t vertices = 0;
};

// Distances from the vertices of the contoured zero set to the true surface.
ZeroSetError zero_set_error(const Domain& domain, const std::vector<double>& f,
                            const Distance& signed_distance) {
  const IsoSurface iso = marching_tetrahedra(domain.mesh(), f);
  ZeroSetError e;
  e.vertices = iso.mesh.vertices.size();
  for (const Vec3& v : iso.mesh.vertices) {
    const double d = std::abs(signed_distance(v));
    e.max = std::max(e.max, d);
    e.mean += d;
  }
  if (e.vertices > 0) e.mean /= static_cast<double>(e.vertices);
  return e;
}

std::ostream& operator<<(std::ostream& out, const ZeroSetError& e) {
  return out << "max " << e.max << ", mean " << e.mean << " (" << e.vertices << " isovertices)";
}

Distance sphere_distance() {
  return [](const Vec3& p) { return p.norm() - 1.0; };
}

const Vec3 kEllipsoidAxes(1.0, 0.7, 0.5);
Distance ellipsoid_distance() {
  return [](const Vec3& p) {
    const double d = test::distance_to_ellipsoid(p, kEllipsoidAxes);
    return p.cwiseQuotient(kEllipsoidAxes).norm() < 1 ? -d : d;
  };
}

Distance torus_distance() {
  return [](const Vec3& p) { return std::hypot(std::hypot(p.x(), p.y()) - 1.0, p.z()) - 0.4; };
}

SolverOptions options_for(SolverKind kind) {
  SolverOptions o;
  o.kind = kind;
  return o;
}

// f < 0 at `inside` and > 0 at every vertex on the domain's sphere.
void expect_signs(const Domain& domain, const std::vector<double>& f, const Vec3& inside) {
  EXPECT_LT(domain.interpolate(inside, f), 0.0);
  int outer = 0, positive = 0;
  for (int v = 0; v < static_cast<int>(domain.num_vertices()); ++v)
    if (domain.on_boundary_sphere(v)) {
      ++outer;
      positive += f[v] > 0;
    }
  ASSERT_GT(outer, 0);
  EXPECT_EQ(positive, outer);
}

// 1% of the bounding-box diagonal, the usual unit of noise.
double one_percent_noise(const PointSet& samples) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : samples.points) box.extend(p);
  return 0.01 * box.diagonal().norm();
}

class EachSolver : public ::testing::TestWithParam<SolverKind> {
 protected:
  std::string name() const { return to_string(GetParam()); }
};

TEST_P(EachSolver, SphereZeroSetIsCloseAndConvergesUnderRefinement) {
  const PointSet samples = test::sample_sphere(2000);
  const Distance d = sphere_distance();
  ZeroSetError coarse, fine;
  for (double h : {0.12, 0.06}) {
    const Domain domain = shell_domain(samples, d, h);
    auto solver = make_solver(options_for(GetParam()));
    const std::vector<double> f = solver->solve(domain, samples);
    ASSERT_EQ(f.size(), domain.num_vertices());
    expect_signs(domain, f, Vec3::Zero());
    const ZeroSetError e = zero_set_error(domain, f, d);
    const SolverStats& s = solver->stats();
    std::cout << name() << " sphere, h = " << h << ": " << e << "; " << domain.num_vertices()
              << " vertices, " << s.method << ", " << s.assembly_seconds << " + "
              << s.factorize_seconds << " + " << s.solve_seconds << " s\n";
    (h > 0.1 ? coarse : fine) = e;
  }
  // Measured: max 0.004-0.006, mean 0.0005-0.0010 at h = 0.06.
  EXPECT_LT(fine.max, 0.015);
  EXPECT_LT(fine.mean, 0.003);
  EXPECT_LT(fine.max, coarse.max);
  EXPECT_LT(fine.mean, coarse.mean);
}

TEST_P(EachSolver, EllipsoidZeroSetIsClose) {
  const PointSet samples = test::sample_ellipsoid(3000, kEllipsoidAxes);
  const Distance d = ellipsoid_distance();
  const Domain domain = shell_domain(samples, d, 0.07, 2);
  auto solver = make_solver(options_for(GetParam()));
  const std::vector<double> f = solver->solve(domain, samples);
  expect_signs(domain, f, Vec3::Zero());
  const ZeroSetError e = zero_set_error(domain, f, d);
  std::cout << name() << " ellipsoid, h = 0.07: " << e << "\n";
  EXPECT_LT(e.max, 0.02);
  EXPECT_LT(e.mean, 0.005);
}

TEST_P(EachSolver, TorusZeroSetIsCloseAndItsHoleIsOutside) {
  const PointSet samples = test::sample_torus(4000, 1.0, 0.4);
  const Distance d = torus_distance();
  const Domain domain = shell_domain(samples, d, 0.07, 3);
  auto solver = make_solver(options_for(GetParam()));
  const std::vector<double> f = solver->solve(domain, samples);
  expect_signs(domain, f, Vec3(1.0, 0.0, 0.0));
  EXPECT_GT(domain.interpolate(Vec3::Zero(), f), 0.0);
  const ZeroSetError e = zero_set_error(domain, f, d);
  std::cout << name() << " torus, h = 0.07: " << e << "\n";
  EXPECT_LT(e.max, 0.02);
  EXPECT_LT(e.mean, 0.005);
}

TEST_P(EachSolver, ScalingTheInputScalesTheZeroSet) {
  // The same triangulation scaled by 4 (exact in binary, and both built by
  // the same constructor so that degenerate cases break alike): the weights
  // are dimensionless, so the zero set must scale with it.
  const PointSet samples = test::sample_sphere(800);
  const Domain built = shell_domain(samples, sphere_distance(), 0.15);
  const Domain domain(built.vertices(), built.flags());
  std::vector<Vec3> scaled_vertices = built.vertices();
  for (Vec3& v : scaled_vertices) v *= 4.0;
  const Domain scaled(scaled_vertices, built.flags());
  PointSet scaled_samples = samples;
  for (Vec3& p : scaled_samples.points) p *= 4.0;
  ASSERT_EQ(scaled.num_tets(), domain.num_tets());

  const std::vector<double> f = make_solver(options_for(GetParam()))->solve(domain, samples);
  const std::vector<double> g =
      make_solver(options_for(GetParam()))->solve(scaled, scaled_samples);
  const IsoSurface a = marching_tetrahedra(domain.mesh(), f);
  const IsoSurface b = marching_tetrahedra(scaled.mesh(), g);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.mesh.vertices.size(); ++i)
    worst = std::max(worst, (4.0 * a.mesh.vertices[i] - b.mesh.vertices[i]).norm());
  EXPECT_LT(worst, 1e-6);
}

// A solver keeps its samples' location order across solves: given other
// points (here fewer of them, on a smaller sphere), it orders them afresh.
TEST_P(EachSolver, OneSolverGivenOtherPointsSolvesAsAFreshOne) {
  const PointSet first = test::sample_sphere(800);
  PointSet second = test::sample_sphere(600);
  for (Vec3& p : second.points) p *= 0.9;
  const Domain domain = shell_domain(first, sphere_distance(), 0.15);
  const auto solver = make_solver(options_for(GetParam()));
  solver->solve(domain, first);
  const std::vector<double> again = solver->solve(domain, second);
  const std::vector<double> fresh = make_solver(options_for(GetParam()))->solve(domain, second);
  ASSERT_EQ(again.size(), fresh.size());
  double worst = 0, scale = 0;
  for (std::size_t v = 0; v < fresh.size(); ++v) {
    worst = std::max(worst, std::abs(again[v] - fresh[v]));
    scale = std::max(scale, std::abs(fresh[v]));
  }
  EXPECT_LT(worst, 1e-4 * scale);
}

TEST_P(EachSolver, MissingNormalsAreAnInputError) {
  PointSet samples = test::sample_sphere(500);
  const Domain domain = Domain::initial(samples);
  samples.normals.clear();
  auto solver = make_solver(options_for(GetParam()));
  EXPECT_TRUE(solver->needs_normals());
  try {
    solver->solve(domain, samples);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no normals"), std::string::npos) << e.what();
  }
}

TEST_P(EachSolver, PointsOutsideTheDomainAreAnInputError) {
  PointSet samples = test::sample_sphere(500);
  const Domain domain = Domain::initial(samples);
  samples.points.push_back(Vec3(10, 0, 0));
  samples.normals.push_back(Vec3(1, 0, 0));
  auto solver = make_solver(options_for(GetParam()));
  try {
    solver->solve(domain, samples);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1 of 501 points"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, EachSolver,
                         ::testing::Values(SolverKind::kPoisson, SolverKind::kSsd,
                                           SolverKind::kSpectral),
                         [](const ::testing::TestParamInfo<SolverKind>& info) {
                           return to_string(info.param);
                         });

class OrientedSolver : public EachSolver {};

TEST_P(OrientedSolver, OnePercentNoiseStaysWithinALooserTolerance) {
  PointSet samples = test::sample_sphere(2000);
  const Distance d = sphere_distance();
  const Domain domain = shell_domain(samples, d, 0.07);
  const double sigma = one_percent_noise(samples);  // 0.035
  test::add_noise(samples, sigma, 5);
  auto solver = make_solver(options_for(GetParam()));
  const std::vector<double> f = solver->solve(domain, samples);
  expect_signs(domain, f, Vec3::Zero());
  const ZeroSetError e = zero_set_error(domain, f, d);
  std::cout << name() << " sphere with noise " << sigma << ": " << e << "\n";
  // Measured: max 0.011 (Poisson), 0.023 (SSD); means 0.003, 0.0045. SSD's
  // value weight follows the noise (solvers.h, ssd_value_weight): with the
  // fixed 4000 of before, max 0.083 and mean 0.015.
  EXPECT_LT(e.max, 3.0 * sigma);
  EXPECT_LT(e.mean, 0.5 * sigma);
}

TEST_P(OrientedSolver, MultigridAgreesWithCholmodAndUsesTheWarmStart) {
  // One domain, no earlier ones: the coarse levels are shares of its vertices.
  const PointSet samples = test::sample_sphere(1000);
  const Domain domain = shell_domain(samples, sphere_distance(), 0.12);
  SolverOptions direct = options_for(GetParam());
  direct.linear.method = LinearMethod::kCholmod;
  SolverOptions iterative = options_for(GetParam());
  iterative.linear.direct_below = 0;
  iterative.linear.coarsest_size = 200;
  iterative.linear.cg_tolerance = 1e-13;
  const std::vector<double> f = make_solver(direct)->solve(domain, samples);
  auto mg = make_solver(iterative);
  const std::vector<double> g = mg->solve(domain, samples);
  const int cold = mg->stats().iterations;
  EXPECT_EQ(mg->stats().method, "cg+multigrid");
  EXPECT_GE(mg->stats().levels, 3);
  EXPECT_GT(cold, 5);
  EXPECT_LE(mg->stats().residual, 1e-12);
  double scale = 0, diff = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    scale = std::max(scale, std::abs(f[i]));
    diff = std::max(diff, std::abs(f[i] - g[i]));
  }
  std::cout << name() << " multigrid against CHOLMOD: " << diff / scale << " relative\n";
  EXPECT_LT(diff, 1e-8 * scale);

  // A warm start off by a scale and a constant (what a median shift and
  // another normalization do) costs almost nothing after the Galerkin
  // correction.
  std::vector<double> warm(g);
  for (double& x : warm) x = 3.0 * x + 0.25 * scale;
  mg->solve(domain, samples, &warm);
  std::cout << name() << " multigrid: " << cold << " iterations cold, " << mg->stats().iterations
            << " warm\n";
  EXPECT_LT(mg->stats().iterations, cold / 4);
}

TEST_P(OrientedSolver, MultigridDoesNotDependOnTheNumberOfThreads) {
  // SSD's matrix is kept as its lower triangle, whose products scatter: in
  // fixed parts, the same bits on one thread and on two. (The prolongations
  // once followed the threads' timing: concurrent CGAL nearest_vertex calls.)
  const PointSet samples = test::sample_sphere(2000);
  const Domain domain = shell_domain(samples, sphere_distance(), 0.07);
  ASSERT_GT(domain.num_vertices(), 4096u);  // several parts of the products
  SolverOptions o = options_for(GetParam());
  o.linear.direct_below = 0;
  o.linear.coarsest_size = 200;
  std::vector<double> f[2];
  for (int threads : {1, 2}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    auto solver = make_solver(o);
    f[threads - 1] = solver->solve(domain, samples);
    EXPECT_EQ(solver->stats().method, "cg+multigrid");
  }
  ASSERT_EQ(f[0].size(), f[1].size());
  for (std::size_t i = 0; i < f[0].size(); ++i) ASSERT_EQ(f[0][i], f[1][i]) << "vertex " << i;
}

INSTANTIATE_TEST_SUITE_P(Solvers, OrientedSolver,
                         ::testing::Values(SolverKind::kPoisson, SolverKind::kSsd),
                         [](const ::testing::TestParamInfo<SolverKind>& info) {
                           return to_string(info.param);
                         });

TEST(SpectralSolver, FlippingHalfOfTheNormalsChangesNothing) {
  PointSet samples = test::sample_ellipsoid(2000, kEllipsoidAxes);
  const Distance d = ellipsoid_distance();
  const Domain domain = shell_domain(samples, d, 0.1);
  auto solver = make_solver(options_for(SolverKind::kSpectral));
  EXPECT_FALSE(solver->needs_oriented_normals());
  const std::vector<double> f = solver->solve(domain, samples);
  std::mt19937 rng(17);
  int flipped = 0;
  for (Vec3& n : samples.normals)
    if (rng() % 2) {
      n = -n;
      ++flipped;
    }
  EXPECT_GT(flipped, 900);
  const std::vector<double> g = solver->solve(domain, samples);
  const ZeroSetError e = zero_set_error(domain, g, d);
  std::cout << "spectral ellipsoid, h = 0.1, half the normals flipped: " << e << "\n";
  EXPECT_LT(e.max, 0.02);
  // C_p = I + mu n n^T does not see the orientation: the same f.
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    diff = std::max(diff, std::abs(f[i] - g[i]));
    scale = std::max(scale, std::abs(f[i]));
  }
  EXPECT_LT(diff, 1e-8 * scale);
  EXPECT_GT(solver->stats().eigenvalue, 0.0);
  EXPECT_LT(solver->stats().residual, 1e-6);
}

TEST(PoissonSolver, WithoutScreeningItIsTheOriginalPoissonEquation) {
  const PointSet samples = test::sample_sphere(2000);
  const Distance d = sphere_distance();
  const Domain domain = shell_domain(samples, d, 0.08);
  SolverOptions o = options_for(SolverKind::kPoisson);
  o.poisson.screened = false;
  auto solver = make_solver(o);
  const std::vector<double> f = solver->solve(domain, samples);
  expect_signs(domain, f, Vec3::Zero());
  const ZeroSetError e = zero_set_error(domain, f, d);
  std::cout << "poisson, not screened: " << e << ", median shift " << solver->stats().median_shift
            << "\n";
  EXPECT_LT(e.max, 0.02);
  EXPECT_NE(solver->stats().median_shift, 0.0);  // the shift places the zero set
  EXPECT_GT(solver->stats().kernel_size, 0.0);
}

// Refined to `sizing` with f the exact signed distance, then one optimizer
// round, as the loop runs before each solve: bisection leaves flat slivers
// (volume 1e-19) whose stiffness is not definite.
void refine_and_optimize(Domain& domain, const Distance& distance, const SizingField& sizing,
                         std::mt19937_64& rng) {
  for (int pass = 0; pass < 6; ++pass) {
    std::vector<double> f(domain.num_vertices());
    for (std::size_t v = 0; v < f.size(); ++v) f[v] = distance(domain.vertices()[v]);
    domain.set_f(f);
    const RefinementStats r = refine(domain, sizing, rng);
    if (r.trisected + r.bisected < 0.02 * r.crossing_tets) break;
  }
  optimize_domain(domain, OptimizerOptions());
}

// Domains refined from each other as the progressive loop refines them (f the
// signed distance, refined by §3.4's rules to a uniform target, then
// optimized), each then solved with the same solver: the earlier domains are its coarse levels.
class ProgressiveLevels : public ::testing::TestWithParam<SolverKind> {};

TEST_P(ProgressiveLevels, MultigridIterationsStayBoundedAndMatchCholmod) {
  struct Shape {
    const char* name;
    PointSet samples;
    Distance distance;
  };
  const Shape shapes[] = {{"sphere", test::sample_sphere(3000), sphere_distance()},
                          {"torus", test::sample_torus(4000, 1.0, 0.4), torus_distance()}};
  for (const Shape& shape : shapes) {
    SolverOptions mg_options = options_for(GetParam());
    mg_options.linear.direct_below = 2000;
    mg_options.linear.coarsest_size = 500;
    auto mg = make_solver(mg_options);
    SolverOptions tight = mg_options;
    tight.linear.cg_tolerance = 1e-13;
    auto mg_tight = make_solver(tight);
    SolverOptions direct = options_for(GetParam());
    direct.linear.method = LinearMethod::kCholmod;
    // The same multigrid with a point (Jacobi) smoother, for SSD.
    SolverOptions point = mg_options;
    point.linear.block_coupling = 1;
    auto mg_point = make_solver(point);
    // And with groups only above 0.5 (the bar before the samples' ties were grouped).
    SolverOptions loose = mg_options;
    loose.linear.block_coupling = 0.5;
    auto mg_loose = make_solver(loose);
    const bool ssd = GetParam() == SolverKind::kSsd;

    Domain domain = Domain::initial(shape.samples);
    std::mt19937_64 rng(3);
    std::vector<int> iterations, point_iterations, loose_iterations;
    for (double edge : {0.2, 0.1, 0.05, 0.025}) {
      refine_and_optimize(domain, shape.distance, *uniform_sizing(area_for_edge_length(edge)), rng);
      const std::vector<double> g = mg->solve(domain, shape.samples);
      const std::vector<double> g_tight = mg_tight->solve(domain, shape.samples);
      if (ssd) {
        mg_point->solve(domain, shape.samples);
        mg_loose->solve(domain, shape.samples);
      }
      if (domain.num_vertices() < mg_options.linear.direct_below) continue;
      EXPECT_EQ(mg->stats().method, "cg+multigrid");
      iterations.push_back(mg->stats().iterations);
      if (ssd) {
        point_iterations.push_back(mg_point->stats().iterations);
        loose_iterations.push_back(mg_loose->stats().iterations);
      }
      const std::vector<double> f = make_solver(direct)->solve(domain, shape.samples);
      double scale = 0, diff = 0;
      for (std::size_t i = 0; i < f.size(); ++i) {
        scale = std::max(scale, std::abs(f[i]));
        diff = std::max(diff, std::abs(f[i] - g_tight[i]));
      }
      std::cout << to_string(GetParam()) << " " << shape.name << ", edge " << edge << ": "
                << domain.num_vertices() << " vertices, " << mg->stats().levels << " levels, "
                << iterations.back() << " iterations to " << mg_options.linear.cg_tolerance
                << (ssd ? " (" + std::to_string(point_iterations.back()) +
                              " with a point smoother, " + std::to_string(loose_iterations.back()) +
                              " with groups above 0.5)"
                        : std::string())
                << "; against CHOLMOD " << diff / scale << " relative\n";
      EXPECT_LT(diff, 1e-8 * scale) << shape.name << ", edge " << edge;
      // The system's unknowns follow a Hilbert curve, not the domain's
      // numbering: a warm start at the solution is taken in the right order
      // (scrambled, it would cost as many iterations as a cold start).
      mg->solve(domain, shape.samples, &g);
      EXPECT_LE(mg->stats().iterations, 1) << shape.name << ", edge " << edge;
    }
    // Counted, not timed, over two refinements of 4x the vertices each: at
    // most 1.5x and one iteration more per refinement (at 7 to 15 iterations
    // the counts move by one or two with the domain's last digits), at most
    // 2x over both (issue 15's bound from 50k to 3M unknowns). Measured:
    // Poisson sphere 11 -> 12 -> 9, torus 13 -> 14 -> 11; SSD sphere
    // 13 -> 13 -> 14, torus 11 -> 13 -> 13. A point smoother does not reach
    // SSD's strongly coupled pairs (block_jacobi.h): sphere 31 -> 36 -> 61,
    // torus 27 -> 33 -> 55; groups above 0.5 only leave the samples' ties to
    // it: sphere 17 -> 20 -> 16, torus 14 -> 18 -> 17.
    ASSERT_EQ(iterations.size(), 3u) << shape.name;
    EXPECT_LE(iterations[2], 2 * iterations[0]) << shape.name;
    EXPECT_LE(iterations[1], 1.5 * iterations[0] + 1) << shape.name;
    EXPECT_LE(iterations[2], 1.5 * iterations[1] + 1) << shape.name;
    if (ssd) {
      EXPECT_GT(point_iterations[2], 2 * iterations[2]) << shape.name;
      EXPECT_GT(loose_iterations[2], iterations[2]) << shape.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, ProgressiveLevels,
                         ::testing::Values(SolverKind::kPoisson, SolverKind::kSsd),
                         [](const ::testing::TestParamInfo<SolverKind>& info) {
                           return to_string(info.param);
                         });

// The loop refines where the isosurface is short of its target, so a
// refinement may add most of its vertices in one region. The coarse levels
// must coarsen there too: made of the earlier domain alone, they missed the
// cap's new vertices and CG took 12 -> 24 iterations (now 12 -> 13;
// docs/benchmarks.md, "Coarse levels drawn from every later iteration").
TEST(ProgressiveLevelsLocal, IterationsStayBoundedAfterALocalRefinement) {
  const PointSet samples = test::sample_sphere(6000);
  SolverOptions o = options_for(SolverKind::kSsd);
  o.linear.direct_below = 2000;
  o.linear.coarsest_size = 500;
  auto solver = make_solver(o);
  Domain domain = Domain::initial(samples);
  std::mt19937_64 rng(5);
  const Distance distance = sphere_distance();
  auto refine_to = [&](const SizingField& sizing) {
    refine_and_optimize(domain, distance, sizing, rng);
    solver->solve(domain, samples);
    return solver->stats();
  };
  refine_to(*uniform_sizing(area_for_edge_length(0.1)));
  const SolverStats before = refine_to(*uniform_sizing(area_for_edge_length(0.05)));
  const std::size_t vertices_before = domain.num_vertices();
  // A cap of a tenth of the sphere refined to a quarter of the edge.
  const SolverStats after = refine_to(*user_sizing([](const Vec3& p) {
    return area_for_edge_length(p.x() > 0.8 ? 0.0125 : 0.05);
  }));
  std::cout << "local refinement: " << vertices_before << " -> " << domain.num_vertices()
            << " vertices, " << before.iterations << " -> " << after.iterations
            << " iterations\n";
  ASSERT_EQ(before.method, "cg+multigrid");
  ASSERT_EQ(after.method, "cg+multigrid");
  ASSERT_GT(domain.num_vertices(), 1.5 * vertices_before);
  EXPECT_LE(after.iterations, 1.5 * before.iterations + 1);
}

TEST(SolverStats, SmallSystemsAreDirectAndLargeOnesMultigrid) {
  const PointSet samples = test::sample_sphere(800);
  const Domain domain = shell_domain(samples, sphere_distance(), 0.15);
  SolverOptions o = options_for(SolverKind::kSsd);
  ASSERT_EQ(o.linear.method, LinearMethod::kMultigrid);
  ASSERT_GT(o.linear.direct_below, domain.num_vertices());
  auto solver = make_solver(o);
  solver->solve(domain, samples);
  EXPECT_EQ(solver->stats().method, "cholmod");
  EXPECT_EQ(solver->stats().levels, 1);
  EXPECT_EQ(solver->stats().iterations, 0);
  EXPECT_EQ(solver->stats().num_vertices, domain.num_vertices());
  EXPECT_EQ(solver->stats().num_points, samples.size());
  EXPECT_GT(solver->stats().nonzeros, domain.num_vertices());
  o.linear.direct_below = domain.num_vertices();
  o.linear.coarsest_size = domain.num_vertices() / 4;
  auto mg = make_solver(o);
  mg->solve(domain, samples);
  EXPECT_EQ(mg->stats().method, "cg+multigrid");
  EXPECT_GE(mg->stats().levels, 2);
  EXPECT_GT(mg->stats().iterations, 0);
  EXPECT_LE(mg->stats().residual, o.linear.cg_tolerance);
}

TEST(SolverOptions, KindsParseAndBadWeightsAreInputErrors) {
  EXPECT_EQ(parse_solver_kind("Poisson"), SolverKind::kPoisson);
  EXPECT_EQ(parse_solver_kind("ssd"), SolverKind::kSsd);
  EXPECT_EQ(parse_solver_kind("SPECTRAL"), SolverKind::kSpectral);
  EXPECT_THROW(parse_solver_kind("rbf"), InputError);
  SolverOptions o;
  o.kind = SolverKind::kSsd;
  o.ssd.alpha = -1;
  EXPECT_THROW(make_solver(o), InputError);
  o.kind = SolverKind::kPoisson;
  o.poisson.alpha = -1;
  EXPECT_THROW(make_solver(o), InputError);
  o = SolverOptions();
  o.linear.cg_tolerance = 0;
  EXPECT_THROW(make_solver(o), InputError);
  o = SolverOptions();
  o.linear.smoothing_degree = 0;
  EXPECT_THROW(make_solver(o), InputError);
  o = SolverOptions();
  o.linear.finest_smoothing_degree = 0;
  EXPECT_THROW(make_solver(o), InputError);
  o = SolverOptions();
  o.linear.coarsening_ratio = 1.1;
  EXPECT_THROW(make_solver(o), InputError);
  EXPECT_EQ(parse_linear_method("Multigrid"), LinearMethod::kMultigrid);
  EXPECT_EQ(parse_linear_method("cholmod"), LinearMethod::kCholmod);
  EXPECT_THROW(parse_linear_method("cg"), InputError);
}

}  // namespace
}  // namespace pdd
