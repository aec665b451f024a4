#include <pdd/errors.h>
#include <pdd/fem.h>
#include <pdd/optimize.h>
#include <pdd/quality.h>
#include <pdd/solvers.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "support/shapes.h"

namespace pdd {
namespace {

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

// The unit sphere's initial domain (radius 1.4) plus a jittered lattice in
// the shell 0.55 < |x| < 1.3 around the sphere.
Domain shell_domain(double spacing = 0.2, unsigned seed = 1) {
  Domain domain = Domain::initial(test::sample_sphere(300));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * spacing, 0.3 * spacing);
  std::vector<Vec3> shell;
  const int k = static_cast<int>(std::ceil(1.5 / spacing));
  for (int i = -k; i <= k; ++i)
    for (int j = -k; j <= k; ++j)
      for (int l = -k; l <= k; ++l) {
        const Vec3 p = spacing * Vec3(i, j, l) + Vec3(jitter(rng), jitter(rng), jitter(rng));
        if (p.norm() > 0.55 && p.norm() < 1.3 && domain.locate(p).tet >= 0) shell.push_back(p);
      }
  domain.insert(shell);
  return domain;
}

std::vector<double> sphere_function(const Domain& domain, double radius = 1.0) {
  std::vector<double> f;
  for (const Vec3& v : domain.vertices()) f.push_back(v.norm() - radius);
  return f;
}

// Where each crossing edge is cut: |t - 1/2|, t in (0, 1] the crossing
// parameter along the edge.
std::vector<double> crossing_offsets(const Domain& domain) {
  std::vector<double> offsets;
  const auto& f = domain.f();
  for (const auto& t : domain.tets())
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double a = f[t[i]], b = f[t[j]];
        if ((a < 0) != (b < 0)) offsets.push_back(std::abs(a / (a - b) - 0.5));
      }
  return offsets;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / v.size();
}

// The vertices of the hull (faces of tets without a neighbour).
std::set<int> hull_vertices(const Domain& domain) {
  std::set<int> hull;
  for (std::size_t t = 0; t < domain.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      if (domain.tet_neighbors()[t][i] < 0)
        for (int k = 0; k < 4; ++k)
          if (k != i) hull.insert(domain.tets()[t][k]);
  return hull;
}

OptimizerOptions only(bool asap, bool mid_edge, bool damping) {
  OptimizerOptions o;
  o.asap = asap;
  o.mid_edge = mid_edge;
  o.damping = damping;
  return o;
}

// Two regular tets with unit edges sharing the face (a, b, c).
Domain regular_bipyramid() {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
  const Vec3 centroid = (a + b + c) / 3;
  const double h = std::sqrt(2.0 / 3.0);
  return Domain({a, b, c, centroid + Vec3(0, 0, h), centroid - Vec3(0, 0, h)});
}

TEST(AsapTerm, GradientVanishesOnRegularTets) {
  Domain domain = regular_bipyramid();
  ASSERT_EQ(domain.num_tets(), 2u);  // equal volumes: the smoothed volume is the volume
  const DomainEnergy energy = domain_energy(domain, only(true, false, false));
  const Eigen::VectorXd x = stacked_positions(domain);
  EXPECT_NEAR(energy.value(x), 0.0, 1e-14);
  EXPECT_LT(energy.gradient(x).norm(), 1e-12);

  // A similar copy (rotated, scaled, moved) is a minimizer too; a distorted
  // one is not.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  std::vector<Vec3> moved;
  for (const Vec3& v : domain.vertices()) moved.push_back(4.2 * R * v + Vec3(3, -1, 2));
  const Domain similar(moved);
  const DomainEnergy e2 = domain_energy(similar, only(true, false, false));
  EXPECT_LT(e2.gradient(stacked_positions(similar)).norm() * e2.diameter, 1e-12);

  moved[0] += Vec3(0.3, -0.2, 0.1);
  const Domain distorted(moved);
  const DomainEnergy e3 = domain_energy(distorted, only(true, false, false));
  EXPECT_GT(e3.gradient(stacked_positions(distorted)).norm() * e3.diameter, 1e-3);
}

TEST(AsapTerm, MinimizerOfOneTetIsRegularWithItsVolume) {
  const Domain domain({Vec3(0, 0, 0), Vec3(2, 0.1, 0), Vec3(0.3, 0.8, 0.1), Vec3(0.2, 0.3, 0.5)});
  ASSERT_EQ(domain.num_tets(), 1u);
  const DomainEnergy energy = domain_energy(domain, only(true, false, false));
  // E is invariant to translations, so A is singular: take the least-norm
  // minimizer, whose centroid is then moved back.
  const Eigen::MatrixXd A = energy.A;
  const Eigen::VectorXd x = A.completeOrthogonalDecomposition().solve(energy.b);
  std::array<Vec3, 4> v;
  for (int i = 0; i < 4; ++i) v[i] = x.segment<3>(3 * i);
  std::vector<double> edges;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) edges.push_back((v[i] - v[j]).norm());
  for (double e : edges) EXPECT_NEAR(e, edges[0], 1e-9);
  const auto& p = domain.vertices();
  EXPECT_NEAR(signed_volume(v[0], v[1], v[2], v[3]), signed_volume(p[0], p[1], p[2], p[3]), 1e-9);
  EXPECT_NEAR(energy.value(x), 0.0, 1e-12);
}

TEST(MidEdgeTerm, GradientVanishesWhenTheIsosurfaceCrossesEdgeMidpoints) {
  Domain domain = shell_domain(0.25);
  // f = +-1: every crossing edge is cut at its midpoint.
  std::vector<double> f = sphere_function(domain);
  for (double& v : f) v = v < 0 ? -1.0 : 1.0;
  domain.set_f(f);
  const DomainEnergy at_midpoints = domain_energy(domain, only(false, true, false));
  ASSERT_GT(at_midpoints.crossing_tets, 100);
  const Eigen::VectorXd x = stacked_positions(domain);
  EXPECT_LT(at_midpoints.gradient(x).norm() * at_midpoints.diameter, 1e-12);
  EXPECT_NEAR(at_midpoints.value(x), 0.0, 1e-14);

  // With the distance, the crossings are off the midpoints.
  domain.set_f(sphere_function(domain));
  const DomainEnergy off = domain_energy(domain, only(false, true, false));
  EXPECT_GT(off.gradient(x).norm() * off.diameter, 1e-4);
}

TEST(MidEdgeTerm, ValueOfOneTetMatchesEquation8) {
  const std::vector<Vec3> p{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  Domain domain(p);
  ASSERT_EQ(domain.num_tets(), 1u);
  // f = 4x + 4y + 4z - 1: crossings at a quarter of the edges from the
  // origin; a_t is the triangle (1/4)(e1, e2, e3), normal (1,1,1)/sqrt(3).
  std::vector<double> f;
  for (const Vec3& v : domain.vertices()) f.push_back(4 * v.sum() - 1);
  domain.set_f(f);
  const DomainEnergy energy = domain_energy(domain, only(false, true, false));
  const double r = std::sqrt(2.0);
  EXPECT_NEAR(energy.diameter, r, 1e-15);
  const double area = std::sqrt(3.0) / 2 / 16;
  const double offset = (0.5 - 0.25) / std::sqrt(3.0);  // ((v0 + v_i)/2 - p_e) . n
  const double expected = 3.0 * area / (r * r) * 3 * offset * offset / (r * r);
  EXPECT_NEAR(energy.value(stacked_positions(domain)), expected, 1e-15);
}

TEST(DampingTerm, WeightsFollowEquation9) {
  Domain domain = shell_domain(0.25);
  domain.set_f(sphere_function(domain));
  const DomainEnergy energy = domain_energy(domain, only(false, false, true));
  const auto& f = domain.f();
  const double f_min = *std::min_element(f.begin(), f.end());
  double fs_min = 1e300;
  for (const auto& t : domain.tets()) {
    int negative = 0;
    for (int v : t) negative += f[v] < 0;
    if (negative > 0 && negative < 4)
      for (int v : t) fs_min = std::min(fs_min, f[v]);
  }
  const double r = energy.diameter;
  int checked = 0;
  for (std::size_t v = 0; v < f.size(); ++v) {
    if (energy.fixed[v]) continue;
    const double weight = energy.A.coeff(3 * v, 3 * v) * r * r;
    if (f[v] >= fs_min && f[v] < 0) {
      EXPECT_EQ(weight, 0.0);
    } else if (f[v] < fs_min) {
      EXPECT_NEAR(weight, 100 * (f[v] - fs_min) / (f_min - fs_min), 1e-9);
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
}

TEST(DampingTerm, KeepsBoundaryVerticesFixedToMachinePrecision) {
  Domain domain = shell_domain();
  domain.set_f(sphere_function(domain));
  const std::vector<Vec3> before = domain.vertices();
  const DomainEnergy energy = domain_energy(domain);
  const OptimizerReport report = optimize_domain(domain);
  EXPECT_GT(report.max_displacement, 1e-4);
  int fixed = 0;
  for (std::size_t v = 0; v < before.size(); ++v) {
    if (domain.on_boundary_sphere(static_cast<int>(v))) {
      EXPECT_TRUE(energy.fixed[v]);
    }
    if (!energy.fixed[v]) continue;
    ++fixed;
    EXPECT_EQ(domain.vertices()[v], before[v]) << "vertex " << v;
  }
  EXPECT_EQ(fixed, report.fixed_vertices);
  EXPECT_GE(fixed, 100);  // the sphere points
  // No vertex left the domain: the hull is the same.
  EXPECT_EQ(hull_vertices(domain), hull_vertices(Domain(before)));
}

TEST(Optimizer, ARoundOnAReleasedTriangulationMovesTheSame) {
  // A round frees the triangulation while it builds and minimizes E(T), and
  // the old one before it builds the new: from a live or a released domain,
  // the same vertices, tets and values; the moved domain comes as its arrays,
  // located over them, and interpolation restores its triangulation.
  Domain live = shell_domain();
  live.set_f(sphere_function(live));
  Domain released = live;
  released.release_triangulation();
  ASSERT_TRUE(released.triangulation_released());
  const OptimizerReport a = optimize_domain(live);
  const OptimizerReport b = optimize_domain(released);
  EXPECT_GT(a.max_displacement, 1e-4);
  EXPECT_EQ(a.max_displacement, b.max_displacement);
  EXPECT_EQ(live.vertices(), released.vertices());
  EXPECT_EQ(live.tets(), released.tets());
  EXPECT_EQ(live.f(), released.f());
  EXPECT_EQ(live.tet_neighbors(), released.tet_neighbors());
  EXPECT_TRUE(released.triangulation_released());
  EXPECT_GE(released.locate(Vec3(0, 0, 0)).tet, 0);
  EXPECT_NEAR(released.interpolate(Vec3(0, 0, 0), released.f()),
              live.interpolate(Vec3(0, 0, 0), live.f()), 1e-12);
  EXPECT_FALSE(released.triangulation_released());
}

TEST(DomainEnergy, QuadraticIsSymmetricPositiveSemiDefiniteOnEdgeBlocks) {
  Domain domain = shell_domain();
  domain.set_f(sphere_function(domain));
  const DomainEnergy energy = domain_energy(domain);
  const Eigen::SparseMatrix<double>& A = energy.A;
  ASSERT_EQ(A.rows(), static_cast<Eigen::Index>(3 * domain.num_vertices()));
  EXPECT_LT((A - Eigen::SparseMatrix<double>(A.transpose())).norm(), 1e-12 * A.norm());
  // Entries only where two vertices share a tet.
  std::set<std::pair<int, int>> pairs;
  for (const auto& t : domain.tets())
    for (int i : t)
      for (int j : t) pairs.insert({i, j});
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      ASSERT_TRUE(pairs.count({static_cast<int>(it.row() / 3), static_cast<int>(j / 3)}));
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x(A.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = normal(rng);
    EXPECT_GE(x.dot(A * x), -1e-12 * A.norm() * x.squaredNorm());
  }
}

TEST(Optimizer, OnePassNeverIncreasesTheEnergy) {
  for (const OptimizerOptions& options :
       {OptimizerOptions{}, only(true, false, true), only(false, true, true), only(true, true, false)}) {
    Domain domain = shell_domain();
    domain.set_f(sphere_function(domain));
    const DomainEnergy energy = domain_energy(domain, options);
    const double before = energy.value(stacked_positions(domain));
    const OptimizerReport report = optimize_domain(domain, options);
    const double after = energy.value(stacked_positions(domain));  // indices are stable
    EXPECT_NEAR(report.energy_before, before, 1e-12 * before);
    EXPECT_NEAR(report.energy_after, after, 1e-9 * before);
    EXPECT_LE(after, before);
    EXPECT_LT(after, 0.9 * before);
    EXPECT_GT(report.cg_iterations, 0);
  }
}

TEST(Optimizer, BadCasesDoNotCrash) {
  // A sliver: four almost coplanar points.
  const double e = 1e-9;
  Domain sliver({Vec3(1, 1, e), Vec3(-1, -1, e), Vec3(1, -1, -e), Vec3(-1, 1, -e)});
  ASSERT_EQ(sliver.num_tets(), 1u);
  sliver.set_f({-1, 1, 1, 1});
  OptimizerReport report;
  EXPECT_NO_THROW(report = optimize_domain(sliver));
  EXPECT_TRUE(std::isfinite(report.energy_before));
  EXPECT_TRUE(std::isfinite(domain_energy(sliver).value(stacked_positions(sliver))));

  // Coplanar points: no tet at all.
  Domain flat({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)});
  EXPECT_NO_THROW(report = optimize_domain(flat));
  EXPECT_EQ(report.cg_iterations, 0);

  // No isosurface: f > 0 everywhere, then f = 0 everywhere (counts as positive).
  for (double value : {1.0, 0.0}) {
    Domain domain = shell_domain(0.3);
    domain.set_f(std::vector<double>(domain.num_vertices(), value));
    EXPECT_NO_THROW(report = optimize_domain(domain));
    EXPECT_EQ(report.crossing_tets, 0);
    EXPECT_LE(report.energy_after, report.energy_before);
  }

  OptimizerOptions bad;
  bad.lambda_asap = -1;
  Domain domain = shell_domain(0.3);
  EXPECT_THROW(optimize_domain(domain, bad), InputError);
}

TEST(Optimizer, InvariantToRigidMotionAndUniformScaling) {
  const Domain source = shell_domain(0.25, 7);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.4).normalized()).toRotationMatrix();
  const double s = 3.7;
  const Vec3 shift(10, -4, 2.5);
  auto transform = [&](const Vec3& v) -> Vec3 { return s * R * v + shift; };

  std::vector<Vec3> moved;
  for (const Vec3& v : source.vertices()) moved.push_back(transform(v));
  Domain a(source.vertices(), source.flags());
  Domain b(moved, source.flags());
  ASSERT_EQ(a.num_tets(), b.num_tets());
  std::vector<double> f = sphere_function(a);
  a.set_f(f);
  for (double& v : f) v *= s;
  b.set_f(f);
  for (int round = 0; round < 2; ++round) {
    const OptimizerReport ra = optimize_domain(a);
    const OptimizerReport rb = optimize_domain(b);
    EXPECT_NEAR(ra.energy_before, rb.energy_before, 1e-9 * ra.energy_before);
    EXPECT_NEAR(ra.energy_after, rb.energy_after, 1e-7 * ra.energy_before);
    EXPECT_EQ(ra.rejected_moves, rb.rejected_moves);
    EXPECT_EQ(ra.cg_iterations, rb.cg_iterations);
  }
  double error = 0, f_error = 0;
  for (std::size_t v = 0; v < a.num_vertices(); ++v) {
    error = std::max(error, (transform(a.vertices()[v]) - b.vertices()[v]).norm());
    f_error = std::max(f_error, std::abs(s * a.f()[v] - b.f()[v]));
  }
  EXPECT_LT(error / s, 1e-9);
  EXPECT_LT(f_error / s, 1e-9);
}

TEST(Optimizer, GuardSendsBackVerticesThatComeTooClose) {
  Domain domain = shell_domain();
  domain.set_f(sphere_function(domain));
  const std::vector<Vec3> before = domain.vertices();
  std::vector<double> shortest(before.size(), 1e300);
  for (const auto& t : domain.tets())
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j) shortest[t[i]] = std::min(shortest[t[i]], (before[t[i]] - before[t[j]]).norm());
  OptimizerOptions options;
  options.min_distance_ratio = 0.9;  // strict: many moves shorten some edge by more than 10%
  const OptimizerReport report = optimize_domain(domain, options);
  EXPECT_GT(report.rejected_moves, 0);
  EXPECT_LE(report.energy_after, report.energy_before);
  int moved = 0;
  for (std::size_t v = 0; v < before.size(); ++v) {
    if (domain.vertices()[v] == before[v]) continue;
    ++moved;
    for (std::size_t u = 0; u < before.size(); ++u) {
      if (u == v) continue;
      ASSERT_GE((domain.vertices()[u] - domain.vertices()[v]).norm(), 0.9 * shortest[v]);
    }
  }
  EXPECT_GT(moved, 100);
  EXPECT_LE(moved + report.rejected_moves + report.fixed_vertices,
            static_cast<int>(before.size()));
}

// Table 2: CG iterations to a relative residual of 1e-10 from 0.
long ssd_cg_iterations(const Domain& domain, const PointSet& input) {
  const ConditioningProbe probe = ssd_conditioning_probe(domain, input);
  EXPECT_TRUE(probe.converged);
  EXPECT_LT(probe.residual, 1e-9);
  return probe.iterations;
}

TEST(Optimizer, AsapRoundsCutTheSsdSolverIterations) {
  const PointSet input = test::sample_sphere(1000);
  Domain domain = Domain::initial(input);
  domain.insert(input.points);
  domain.set_f(make_solver({})->solve(domain, input));  // SSD
  const long before = ssd_cg_iterations(domain, input);
  OptimizerOptions asap;
  asap.mid_edge = false;
  for (int round = 0; round < 10; ++round) optimize_domain(domain, asap);
  const long after = ssd_cg_iterations(domain, input);
  std::printf("SSD CG iterations: %ld -> %ld after 10 ASAP rounds\n", before, after);
  EXPECT_LT(after, 0.7 * before);
}

TEST(Optimizer, RoundsImproveTetsAndBringCrossingsToMidpoints) {
  Domain domain = shell_domain();
  domain.set_f(sphere_function(domain));
  const TetQuality q0 = tet_quality(domain.mesh());
  const std::vector<double> o0 = crossing_offsets(domain);
  for (int round = 0; round < 5; ++round) {
    const OptimizerReport report = optimize_domain(domain);
    EXPECT_LE(report.energy_after, report.energy_before);
    domain.set_f(sphere_function(domain));  // a perfect solver
  }
  const TetQuality q5 = tet_quality(domain.mesh());
  const std::vector<double> o5 = crossing_offsets(domain);
  auto near_midpoint = [](const std::vector<double>& o) {
    return std::count_if(o.begin(), o.end(), [](double t) { return t <= 0.1; }) /
           static_cast<double>(o.size());
  };
  std::printf("min dihedral %.2f -> %.2f, below 10 deg %.4f -> %.4f, crossings offset %.3f -> %.3f, "
              "within 10%% of midpoint %.3f -> %.3f\n",
              q0.min_dihedral, q5.min_dihedral, q0.fraction_min_dihedral_below_10,
              q5.fraction_min_dihedral_below_10, mean(o0), mean(o5), near_midpoint(o0),
              near_midpoint(o5));
  EXPECT_GT(q5.mean_min_dihedral, q0.mean_min_dihedral);
  EXPECT_LT(q5.fraction_min_dihedral_below_10, q0.fraction_min_dihedral_below_10);
  EXPECT_LT(mean(o5), 0.8 * mean(o0));
  EXPECT_GT(near_midpoint(o5), near_midpoint(o0) + 0.1);
}

}  // namespace
}  // namespace pdd
