// The piecewise-linear operators of §3.5 on generated tetrahedral meshes:
// identities that hold exactly for linear functions, the cotangent formula
// of Eq. (12) against G^T M_T G, sampling and selection matrices.
#include <pdd/domain.h>
#include <pdd/errors.h>
#include <pdd/fem.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace pdd {
namespace {

// A Delaunay mesh of the unit cube [0,1]^3: a jittered interior lattice plus
// the exact corners and lattice points on the faces (so the hull is the cube).
Domain cube_domain(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<Vec3> points;
  const double h = 1.0 / n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        Vec3 p(i * h, j * h, k * h);
        // Jitter only the coordinates that are not on a face of the cube.
        if (i > 0 && i < n) p.x() += jitter(rng) * h;
        if (j > 0 && j < n) p.y() += jitter(rng) * h;
        if (k > 0 && k < n) p.z() += jitter(rng) * h;
        points.push_back(p);
      }
  return Domain(points);
}

// Vertices on the boundary of the mesh: those of a facet without a neighbour.
std::vector<bool> hull_vertices(const Domain& d) {
  std::vector<bool> hull(d.num_vertices(), false);
  for (std::size_t t = 0; t < d.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      if (d.tet_neighbors()[t][i] < 0)
        for (int k = 0; k < 4; ++k)
          if (k != i) hull[d.tets()[t][k]] = true;
  return hull;
}

Eigen::VectorXd linear_function(const TetMesh& m, const Vec3& a, double c) {
  Eigen::VectorXd f(m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) f[i] = a.dot(m.vertices[i]) + c;
  return f;
}

class FemTest : public ::testing::Test {
 protected:
  void SetUp() override {
    domain = cube_domain(8, 7);
    mesh = domain.mesh();
  }
  Domain domain;
  TetMesh mesh;
};

TEST_F(FemTest, VolumesAndMassesSumToTheCubeVolume) {
  const Eigen::VectorXd vol = tet_volumes(mesh);
  const Eigen::VectorXd mass = vertex_masses(mesh);
  ASSERT_EQ(vol.size(), static_cast<Eigen::Index>(mesh.tets.size()));
  ASSERT_EQ(mass.size(), static_cast<Eigen::Index>(mesh.vertices.size()));
  EXPECT_GT(vol.minCoeff(), 0.0);
  EXPECT_NEAR(vol.sum(), 1.0, 1e-12);
  EXPECT_NEAR(mass.sum(), 1.0, 1e-12);
}

TEST_F(FemTest, GradientOfALinearFunctionIsExact) {
  const SparseMatrix G = gradient_matrix(mesh);
  ASSERT_EQ(G.rows(), 3 * static_cast<Eigen::Index>(mesh.tets.size()));
  ASSERT_EQ(G.cols(), static_cast<Eigen::Index>(mesh.vertices.size()));
  const Vec3 a(0.3, -1.7, 2.2);
  const Eigen::VectorXd g = G * linear_function(mesh, a, 0.9);
  double worst = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    worst = std::max(worst, (g.segment<3>(3 * t) - a).norm());
  EXPECT_LT(worst, 1e-10);
}

TEST_F(FemTest, LaplacianAnnihilatesConstantsAndIsSymmetricPositive) {
  const SparseMatrix L = cotangent_laplacian(mesh);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(L.cols());
  EXPECT_LT((L * ones).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(SparseMatrix(L - SparseMatrix(L.transpose())).norm(), 1e-12 * L.norm());
  EXPECT_GT(L.diagonal().minCoeff(), 0.0);
  // Positive semi-definite: x^T L x >= 0 for random x.
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x(L.cols());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = g(rng);
    EXPECT_GT(x.dot(L * x), 0.0);
  }
}

TEST_F(FemTest, CotangentLaplacianEqualsGTransposeMG) {
  const SparseMatrix L = cotangent_laplacian(mesh);
  const SparseMatrix G = gradient_matrix(mesh);
  const Eigen::VectorXd vol = tet_volumes(mesh);
  Eigen::VectorXd mt(3 * vol.size());
  for (Eigen::Index t = 0; t < vol.size(); ++t) mt.segment<3>(3 * t).setConstant(vol[t]);
  const SparseMatrix K = SparseMatrix(G.transpose()) * mt.asDiagonal() * G;
  EXPECT_LT(SparseMatrix(L - K).norm(), 1e-10 * L.norm());
  // Same sparsity: one entry per vertex and per edge.
  EXPECT_EQ(L.nonZeros(), K.nonZeros());

  // G^T W G with W_t = vol_t I is the same matrix.
  std::vector<Eigen::Matrix3d> w(mesh.tets.size());
  for (std::size_t t = 0; t < w.size(); ++t) w[t] = vol[t] * Eigen::Matrix3d::Identity();
  EXPECT_LT(SparseMatrix(weighted_stiffness(mesh, w) - L).norm(), 1e-10 * L.norm());
  // And with the scalar weights W_t = vol_t.
  const std::vector<double> scalar(vol.data(), vol.data() + vol.size());
  EXPECT_LT(SparseMatrix(weighted_stiffness(mesh, scalar) - L).norm(), 1e-10 * L.norm());
  EXPECT_THROW(weighted_stiffness(mesh, std::vector<double>(3, 1.0)), std::invalid_argument);
}

TEST_F(FemTest, LaplacianOfALinearFunctionVanishesInside) {
  const SparseMatrix L = cotangent_laplacian(mesh);
  const Eigen::VectorXd Lf = L * linear_function(mesh, Vec3(1, 2, -3), 0.5);
  const std::vector<bool> hull = hull_vertices(domain);
  int interior = 0;
  for (Eigen::Index v = 0; v < Lf.size(); ++v)
    if (!hull[v]) {
      ++interior;
      EXPECT_NEAR(Lf[v], 0.0, 1e-10) << "vertex " << v;
    }
  EXPECT_GT(interior, 300);
}

TEST_F(FemTest, HessianOfALinearFunctionVanishesAtInteriorVertices) {
  const SparseMatrix H = hessian_matrix(mesh);
  const Eigen::Index n = static_cast<Eigen::Index>(mesh.vertices.size());
  ASSERT_EQ(H.rows(), 9 * n);
  ASSERT_EQ(H.cols(), n);
  const Vec3 a(0.4, -1.1, 0.7);
  const Eigen::VectorXd Hf = H * linear_function(mesh, a, -2.0);
  const std::vector<bool> hull = hull_vertices(domain);
  double interior_worst = 0, boundary_worst = 0;
  for (Eigen::Index v = 0; v < n; ++v)
    for (int ab = 0; ab < 9; ++ab) {
      const double value = std::abs(Hf[ab * n + v]);
      (hull[v] ? boundary_worst : interior_worst) =
          std::max(hull[v] ? boundary_worst : interior_worst, value);
    }
  EXPECT_LT(interior_worst, 1e-12);
  // On the hull the weak form keeps its boundary term d_a f * int phi_v n_b:
  // a vertex in the middle of the face x = 1 (outer normal +x) gets
  // a_x * (area of its star on that face) in component (a, b) = (x, x).
  EXPECT_GT(boundary_worst, 1e-4);
}

TEST_F(FemTest, HessianOfAQuadraticIsItsMatrixOnAverage) {
  // f = x^T Q x / 2 has Hessian Q; (H f)_v = -int phi_v Q = -Q m_v at
  // interior vertices for the exact f. The P1 interpolant is close to it;
  // summed over the interior the errors largely cancel.
  Eigen::Matrix3d Q;
  Q << 2.0, 0.5, -0.3, 0.5, -1.0, 0.8, -0.3, 0.8, 1.5;
  const SparseMatrix H = hessian_matrix(mesh);
  const Eigen::VectorXd mass = vertex_masses(mesh);
  const Eigen::Index n = static_cast<Eigen::Index>(mesh.vertices.size());
  Eigen::VectorXd f(n);
  for (Eigen::Index v = 0; v < n; ++v) f[v] = 0.5 * mesh.vertices[v].dot(Q * mesh.vertices[v]);
  const Eigen::VectorXd Hf = H * f;
  const std::vector<bool> hull = hull_vertices(domain);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  double interior_mass = 0;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (hull[v]) continue;
    interior_mass += mass[v];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) sum(a, b) += Hf[(3 * a + b) * n + v];
  }
  EXPECT_LT((sum / interior_mass + Q).norm(), 0.05 * Q.norm());
}

TEST_F(FemTest, GramMatrixMatchesEigensProduct) {
  const SparseMatrix H = hessian_matrix(mesh);
  const Eigen::VectorXd mass = vertex_masses(mesh);
  Eigen::VectorXd d(H.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = 1.0 / mass[i % mass.size()];
  const SparseMatrix mine = gram_matrix(H, d);
  const SparseMatrix eigen = SparseMatrix(H.transpose()) * d.asDiagonal() * H;
  EXPECT_LT(SparseMatrix(mine - eigen).norm(), 1e-12 * eigen.norm());
  EXPECT_EQ(mine.nonZeros(), eigen.nonZeros());
  // Row indices sorted in every column, as Eigen requires.
  for (Eigen::Index j = 0; j < mine.cols(); ++j)
    for (int p = mine.outerIndexPtr()[j] + 1; p < mine.outerIndexPtr()[j + 1]; ++p)
      ASSERT_LT(mine.innerIndexPtr()[p - 1], mine.innerIndexPtr()[p]);
}

TEST_F(FemTest, GalerkinProductMatchesEigensProduct) {
  // The multigrid's coarse operator P^T A P: A the squared Hessian (two-ring),
  // P a prolongation's shape (a unit row for every third vertex, up to four
  // weights summing to 1 for the others); 733 coarse columns, so that the
  // product's chunks of 256 columns meet.
  const SparseMatrix A = hessian_energy(cube_domain(12, 3).mesh());
  const int n = static_cast<int>(A.rows()), m = (n + 2) / 3;
  std::vector<Eigen::Triplet<double>> entries;
  std::mt19937 rng(5);
  for (int r = 0; r < n; ++r) {
    if (r % 3 == 0) {
      entries.emplace_back(r, r / 3, 1.0);
      continue;
    }
    double w[4], sum = 0;
    for (double& x : w) sum += (x = 0.1 + std::uniform_real_distribution<double>()(rng));
    for (int k = 0; k < 4; ++k) entries.emplace_back(r, (r / 3 + 7 * k) % m, w[k] / sum);
  }
  SparseMatrix P(n, m);
  P.setFromTriplets(entries.begin(), entries.end());
  P.makeCompressed();
  const SparseMatrix mine = galerkin_product(P, A);
  const SparseMatrix eigen = SparseMatrix(P.transpose()) * A * P;
  EXPECT_LT(SparseMatrix(mine - eigen).norm(), 1e-12 * eigen.norm());
  EXPECT_EQ(mine.nonZeros(), eigen.nonZeros());
  for (Eigen::Index j = 0; j < mine.cols(); ++j)
    for (int p = mine.outerIndexPtr()[j] + 1; p < mine.outerIndexPtr()[j + 1]; ++p)
      ASSERT_LT(mine.innerIndexPtr()[p - 1], mine.innerIndexPtr()[p]);

  // `got` has want's pattern and its values within `tolerance`.
  auto expect_close = [](const auto& got, const SparseMatrix& want, double tolerance) {
    ASSERT_EQ(got.nonZeros(), want.nonZeros());
    for (Eigen::Index k = 0; k < want.nonZeros(); ++k) {
      ASSERT_EQ(got.innerIndexPtr()[k], want.innerIndexPtr()[k]);
      ASSERT_LE(std::abs(double(got.valuePtr()[k]) - want.valuePtr()[k]), tolerance);
    }
  };

  // From A's lower triangle alone: the same pattern, the same values but
  // for the order of the sums, whole or as a lower triangle too.
  const SparseMatrix lower = A.triangularView<Eigen::Lower>();
  expect_close(galerkin_product(P, lower, Stored::kLower, Stored::kAll), mine,
               1e-13 * eigen.norm());
  const SparseMatrix mine_lower = mine.triangularView<Eigen::Lower>();
  ASSERT_LT(mine_lower.nonZeros(), mine.nonZeros());
  for (const Stored stored : {Stored::kAll, Stored::kLower})
    expect_close(galerkin_product(P, stored == Stored::kAll ? A : lower, stored, Stored::kLower),
                 mine_lower, 1e-13 * eigen.norm());

  // In single precision (the multigrid's coarse levels): from A in double,
  // each entry is the double product's rounded once; from A in single, and
  // from A's lower triangle in double (the multigrid's first coarse level,
  // the entries above the diagonal read rounded), within float's rounding of
  // it. The same pattern.
  const Eigen::SparseMatrix<float> from_double = galerkin_product<float>(P, A);
  ASSERT_EQ(from_double.nonZeros(), mine.nonZeros());
  for (Eigen::Index k = 0; k < mine.nonZeros(); ++k) {
    ASSERT_EQ(from_double.innerIndexPtr()[k], mine.innerIndexPtr()[k]);
    ASSERT_EQ(from_double.valuePtr()[k], static_cast<float>(mine.valuePtr()[k]));
  }
  const double largest = mine.coeffs().cwiseAbs().maxCoeff();
  const Eigen::SparseMatrix<float> A_single = A.cast<float>();
  expect_close(galerkin_product<float>(P, A_single), mine, 1e-6 * largest);
  expect_close(galerkin_product<float>(P, lower, Stored::kLower, Stored::kLower), mine_lower,
               1e-6 * largest);
}

// H^T M^-1 H, the squared Hessian energy by its definition.
SparseMatrix hessian_energy_by_definition(const TetMesh& m) {
  const SparseMatrix H = hessian_matrix(m);
  const Eigen::VectorXd mass = vertex_masses(m);
  Eigen::VectorXd d(H.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = 1.0 / mass[i % mass.size()];
  return gram_matrix(H, d);
}

TEST_F(FemTest, HessianEnergyIsHTransposeMassInverseH) {
  const SparseMatrix expected = hessian_energy_by_definition(mesh);
  const SparseMatrix energy = hessian_energy(mesh);
  const Eigen::VectorXd mass = vertex_masses(mesh);
  EXPECT_LT(SparseMatrix(energy - expected).norm(), 1e-12 * expected.norm());
  // It is the squared Hessian: zero for linear functions away from the hull,
  // and f^T E f > 0 for a quadratic.
  Eigen::VectorXd q(mass.size());
  for (Eigen::Index v = 0; v < q.size(); ++v) q[v] = mesh.vertices[v].squaredNorm();
  EXPECT_GT(q.dot(energy * q), 0.0);
}

TEST_F(FemTest, HessianEnergysLowerTriangleIsTheSameEntries) {
  const SparseMatrix all = hessian_energy(mesh);
  const SparseMatrix lower = hessian_energy(mesh, Stored::kLower);
  const SparseMatrix expected = all.triangularView<Eigen::Lower>();
  ASSERT_EQ(lower.nonZeros(), expected.nonZeros());
  ASSERT_EQ(2 * lower.nonZeros() - lower.rows(), all.nonZeros());
  for (Eigen::Index k = 0; k < lower.nonZeros(); ++k) {
    ASSERT_EQ(lower.innerIndexPtr()[k], expected.innerIndexPtr()[k]);
    ASSERT_EQ(lower.valuePtr()[k], expected.valuePtr()[k]);
  }
}

// SSD adds its samples' terms into the Hessian energy in place, from the
// sampled tets alone: the products of Eq. (15) by their definitions.
TEST_F(FemTest, SampleTermsAddedInPlaceAreTheProductsOfEquation15) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> points, normals;
  for (int i = 0; i < 600; ++i) {
    points.emplace_back(u(rng), u(rng), u(rng));
    normals.push_back(Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized());
  }
  const std::vector<Location> loc = locate_points(domain, points);
  std::vector<int> per_tet(mesh.tets.size(), 0);
  for (const Location& l : loc) ++per_tet[l.tet];
  ASSERT_GT(*std::max_element(per_tet.begin(), per_tet.end()), 1);  // tets with several samples
  const SparseMatrix Phi = sampling_matrix(mesh, loc);
  const SparseMatrix SG = selection_matrix(mesh.tets.size(), loc) * gradient_matrix(mesh);
  Eigen::VectorXd N(3 * points.size());
  for (std::size_t p = 0; p < points.size(); ++p) N.segment<3>(3 * p) = normals[p];
  const double beta = 0.7, alpha = 3.5;
  const SparseMatrix added = beta * SparseMatrix(SG.transpose() * SG) +
                             alpha * SparseMatrix(Phi.transpose() * Phi);
  const Eigen::VectorXd expected_b = SG.transpose() * N;
  for (const Stored stored : {Stored::kAll, Stored::kLower}) {
    const SparseMatrix energy = hessian_energy(mesh, stored);
    SparseMatrix in_place = energy;
    const SparseMatrix expected =
        energy + (stored == Stored::kLower ? SparseMatrix(added.triangularView<Eigen::Lower>())
                                           : added);
    const Eigen::VectorXd b = add_sample_terms(in_place, mesh, loc, normals, beta, alpha, stored);
    ASSERT_EQ(in_place.nonZeros(), energy.nonZeros());  // no new entry
    EXPECT_LT(SparseMatrix(in_place - expected).norm(), 1e-14 * expected.norm());
    EXPECT_GT(SparseMatrix(in_place - energy).norm(), 0.1 * added.norm());
    EXPECT_LT((b - expected_b).norm(), 1e-14 * expected_b.norm());
  }
  // A pattern without the one-rings (the diagonal alone) cannot take them.
  SparseMatrix diagonal(static_cast<Eigen::Index>(mesh.vertices.size()),
                        static_cast<Eigen::Index>(mesh.vertices.size()));
  diagonal.setIdentity();
  EXPECT_THROW(add_sample_terms(diagonal, mesh, loc, normals, 1.0, 1.0), std::logic_error);
  EXPECT_THROW(add_sample_terms(diagonal, mesh, loc, std::vector<Vec3>(3), 1.0, 1.0),
               std::invalid_argument);
}

// hessian_energy assembles H a slice of columns at a time (32768): on a mesh
// of several slices, whose vertices are numbered at random, it is still
// H^T M^-1 H.
TEST(Fem, HessianEnergyOverSeveralSlicesIsHTransposeMassInverseH) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> points;
  for (int i = 0; i < 40000; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const TetMesh big = Domain(points).mesh();
  ASSERT_GT(big.vertices.size(), 32768u);
  const SparseMatrix expected = hessian_energy_by_definition(big);
  const SparseMatrix energy = hessian_energy(big);
  EXPECT_EQ(energy.nonZeros(), expected.nonZeros());
  EXPECT_LT(SparseMatrix(energy - expected).norm(), 1e-12 * expected.norm());
}

TEST_F(FemTest, SamplingMatrixInterpolatesLinearFunctionsExactly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const std::vector<Location> loc = locate_points(domain, points);
  const SparseMatrix Phi = sampling_matrix(mesh, loc);
  ASSERT_EQ(Phi.rows(), 500);
  ASSERT_EQ(Phi.cols(), static_cast<Eigen::Index>(mesh.vertices.size()));
  const Vec3 a(1.5, 0.2, -0.8);
  const Eigen::VectorXd values = Phi * linear_function(mesh, a, 0.25);
  const Eigen::VectorXd row_sums = Phi * Eigen::VectorXd::Ones(Phi.cols());
  for (int i = 0; i < 500; ++i) {
    EXPECT_NEAR(values[i], a.dot(points[i]) + 0.25, 1e-12);
    EXPECT_NEAR(row_sums[i], 1.0, 1e-12);
  }
}

// A caller that keeps the location order gets the same locations; an order
// of other points is refused.
TEST_F(FemTest, PointsLocatedInAGivenOrderLandAsInTheirOwn) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < 700; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const std::vector<std::size_t> order = location_order(points);
  ASSERT_EQ(order.size(), points.size());
  EXPECT_EQ(std::set<std::size_t>(order.begin(), order.end()).size(), points.size());
  const std::vector<Location> own = locate_points(domain, points);
  const std::vector<Location> given = locate_points(domain, points, &order);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(given[i].tet, own[i].tet);
    EXPECT_EQ(given[i].barycentric, own[i].barycentric);
  }
  const std::vector<std::size_t> shorter(order.begin(), order.end() - 1);
  EXPECT_THROW(locate_points(domain, points, &shorter), std::invalid_argument);
}

// Thousands of samples in a domain of 30k vertices: located in spatial order
// from one another's tets, each lands in a tet that holds it, as a walk from
// scratch (Domain::locate) finds.
TEST(Sampling, LocatedFromTheirNeighboursPointsLieInTheirTets) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> corners_and_inside;
  for (int i = 0; i < 8; ++i) corners_and_inside.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  for (int i = 0; i < 30000; ++i) corners_and_inside.emplace_back(u(rng), u(rng), u(rng));
  const Domain domain(corners_and_inside);
  std::vector<Vec3> points;
  for (int i = 0; i < 5000; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  const auto& x = domain.vertices();
  std::vector<double> values;  // a function that differs from tet to tet
  for (const Vec3& v : x) values.push_back(v.squaredNorm());
  // With CGAL's triangulation, then walking the tets' arrays once it is released.
  for (const bool released : {false, true}) {
    if (released) domain.release_triangulation();
    const std::vector<Location> loc = locate_points(domain, points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_GE(loc[i].tet, 0);
      const auto& tet = domain.tets()[loc[i].tet];
      Vec3 p = Vec3::Zero();
      for (int k = 0; k < 4; ++k) {
        EXPECT_GE(loc[i].barycentric[k], -1e-12);
        p += loc[i].barycentric[k] * x[tet[k]];
      }
      EXPECT_LT((p - points[i]).norm(), 1e-12) << (released ? "released" : "");
      const Location alone = domain.locate(points[i]);
      EXPECT_NEAR(domain.interpolate(loc[i], values), domain.interpolate(alone, values), 1e-12);
    }
  }
}

TEST_F(FemTest, SelectionMatrixPicksTheGradientOfEachPointsTet) {
  const std::vector<Vec3> points = {Vec3(0.5, 0.5, 0.5), Vec3(0.1, 0.9, 0.2),
                                    Vec3(0.5, 0.5, 0.5)};
  const std::vector<Location> loc = locate_points(domain, points);
  const SparseMatrix S = selection_matrix(mesh.tets.size(), loc);
  ASSERT_EQ(S.rows(), 9);
  ASSERT_EQ(S.cols(), 3 * static_cast<Eigen::Index>(mesh.tets.size()));
  const Vec3 a(-0.6, 0.1, 2.0);
  const Eigen::VectorXd g = S * (gradient_matrix(mesh) * linear_function(mesh, a, 1.0));
  for (int p = 0; p < 3; ++p) EXPECT_LT((g.segment<3>(3 * p) - a).norm(), 1e-10);
  // S^T S counts the points in each tet: the first and third share theirs.
  const SparseMatrix StS = SparseMatrix(S.transpose()) * S;
  EXPECT_DOUBLE_EQ(StS.coeff(3 * loc[0].tet, 3 * loc[0].tet), loc[0].tet == loc[1].tet ? 3 : 2);
}

TEST_F(FemTest, PointsOutsideTheDomainAreAnInputErrorNamingHowMany) {
  const std::vector<Vec3> points = {Vec3(0.5, 0.5, 0.5), Vec3(2, 0, 0), Vec3(0.2, 0.2, 0.2),
                                    Vec3(0, -1, 0)};
  try {
    locate_points(domain, points);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2 of 4 points"), std::string::npos) << e.what();
  }
}

TEST_F(FemTest, AssemblyDoesNotDependOnTheNumberOfThreads) {
  SparseMatrix one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = hessian_matrix(mesh);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = hessian_matrix(mesh);
  }
  ASSERT_EQ(one.nonZeros(), two.nonZeros());
  for (Eigen::Index k = 0; k < one.nonZeros(); ++k) {
    ASSERT_EQ(one.valuePtr()[k], two.valuePtr()[k]);
    ASSERT_EQ(one.innerIndexPtr()[k], two.innerIndexPtr()[k]);
  }
}

}  // namespace
}  // namespace pdd
