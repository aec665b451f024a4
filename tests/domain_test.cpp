#include <pdd/domain.h>
#include <pdd/errors.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <random>
#include <utility>

#include "support/shapes.h"

namespace pdd {
namespace {

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

std::vector<Vec3> random_points_in_ball(int n, double radius, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-radius, radius);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < n) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.norm() < radius) points.push_back(p);
  }
  return points;
}

// The tets as sets of corners, in sorted order: the same triangulation
// whatever the tets' numbering.
std::vector<std::array<int, 4>> sorted(std::vector<std::array<int, 4>> tets) {
  for (auto& t : tets) std::sort(t.begin(), t.end());
  std::sort(tets.begin(), tets.end());
  return tets;
}

TEST(InitialDomain, MeetsRadiusEdgeBoundAndContainsInput) {
  const PointSet input = test::sample_ellipsoid(2000, Vec3(1.0, 0.6, 0.3));
  RefinementReport report;
  const Domain d = Domain::initial(input, {}, &report);
  EXPECT_EQ(report.remaining_bad, 0);
  EXPECT_LE(report.worst_radius_edge, 1.3);
  for (const auto& t : d.tets())
    EXPECT_LE(radius_edge_ratio(d.vertices()[t[0]], d.vertices()[t[1]], d.vertices()[t[2]],
                                d.vertices()[t[3]]),
              1.3 + 1e-12);
  for (const Vec3& p : input.points) EXPECT_GE(d.locate(p).tet, 0);
}

TEST(InitialDomain, SphereVerticesLieOnTheEnlargedBoundingSphere) {
  const PointSet input = test::sample_sphere(300, 2.0, Vec3(1, -1, 3));
  DomainOptions options;
  const Domain d = Domain::initial(input, options);
  EXPECT_NEAR(d.radius(), 1.4 * 2.0, 1e-9);
  EXPECT_LT((d.center() - Vec3(1, -1, 3)).norm(), 1e-9);
  int on_sphere = 0;
  for (std::size_t i = 0; i < d.num_vertices(); ++i) {
    const double distance = (d.vertices()[i] - d.center()).norm();
    if (d.on_boundary_sphere(static_cast<int>(i))) {
      ++on_sphere;
      EXPECT_NEAR(distance, d.radius(), 1e-9);
    } else {
      EXPECT_LT(distance, d.radius());
    }
  }
  EXPECT_GE(on_sphere, options.sphere_points);
}

TEST(InitialDomain, IsDeterministic) {
  const PointSet input = test::sample_torus(1500, 1.0, 0.3);
  const Domain a = Domain::initial(input);
  const Domain b = Domain::initial(input);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  EXPECT_EQ(a.vertices(), b.vertices());
  EXPECT_EQ(a.tets(), b.tets());
}

TEST(InitialDomain, RejectsBadOptions) {
  const PointSet input = test::sample_sphere(50);
  DomainOptions options;
  options.enlarge_ratio = 0.9;
  EXPECT_THROW(Domain::initial(input, options), InputError);
  options.enlarge_ratio = 101;
  EXPECT_THROW(Domain::initial(input, options), InputError);
  options = DomainOptions();
  options.radius_edge_bound = 0.9;
  EXPECT_THROW(Domain::initial(input, options), InputError);
  EXPECT_THROW(Domain::initial(PointSet{}), InputError);
}

// The domain is the hull of the sphere's points: too few of them, or too
// small a sphere, leave part of the input's bounding sphere outside it.
TEST(InitialDomain, TheHullOfTheSpherePointsMustHoldTheInput) {
  const PointSet input = test::sample_sphere(300);
  DomainOptions options;
  options.sphere_points = 4;
  try {
    Domain::initial(input, options);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the hull of 4 points on the domain sphere "
                                         "(--sphere-points) reaches 0.227 of its radius"),
              std::string::npos)
        << e.what();
  }
  options.enlarge_ratio = 4.5;
  const Domain d = Domain::initial(input, options);
  for (const Vec3& p : input.points) EXPECT_GE(d.locate(p).tet, 0);
  options = DomainOptions();
  options.enlarge_ratio = 1.01;
  EXPECT_THROW(Domain::initial(input, options), InputError);
  options.sphere_points = 2000;
  EXPECT_NO_THROW(Domain::initial(input, options));
}

TEST(Domain, TranslateMovesVerticesAndCentreKeepingTetsAndF) {
  Domain d = Domain::initial(test::sample_sphere(200));
  std::vector<double> f(d.num_vertices());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = d.vertices()[i].x();
  d.set_f(f);
  const Domain before = d;
  const Vec3 offset(5e5, -5e6, 3);
  d.translate(offset);
  EXPECT_EQ(d.tets(), before.tets());
  EXPECT_EQ(d.f(), f);
  EXPECT_EQ(d.center(), before.center() + offset);
  for (std::size_t i = 0; i < d.num_vertices(); ++i)
    EXPECT_EQ(d.vertices()[i], before.vertices()[i] + offset);
  // Located and interpolated where it now is.
  const Vec3 p = before.vertices()[7] * 0.5;
  EXPECT_NEAR(d.interpolate(p + offset, f), before.interpolate(p, f), 1e-6);
}

TEST(Domain, TetsArePositivelyOrientedAndNeighborsAreSymmetric) {
  const Domain d(random_points_in_ball(400, 1.0, 3));
  ASSERT_GT(d.num_tets(), 0u);
  const auto& v = d.vertices();
  for (const auto& t : d.tets()) EXPECT_GT(signed_volume(v[t[0]], v[t[1]], v[t[2]], v[t[3]]), 0);
  const auto& nb = d.tet_neighbors();
  for (std::size_t t = 0; t < d.num_tets(); ++t)
    for (int i = 0; i < 4; ++i) {
      const int n = nb[t][i];
      if (n < 0) continue;
      int back = 0;
      for (int j = 0; j < 4; ++j) back += nb[n][j] == static_cast<int>(t);
      EXPECT_EQ(back, 1);
    }
}

TEST(Domain, InterpolationReproducesLinearFunctionsExactly) {
  Domain d(random_points_in_ball(500, 1.0, 4));
  std::vector<double> f;
  auto linear = [](const Vec3& p) { return 0.5 + 2 * p.x() - 3 * p.y() + 0.25 * p.z(); };
  for (const Vec3& p : d.vertices()) f.push_back(linear(p));
  for (const Vec3& q : random_points_in_ball(200, 0.5, 5)) {
    const Location loc = d.locate(q);
    ASSERT_GE(loc.tet, 0);
    double sum = 0;
    for (double w : loc.barycentric) {
      EXPECT_GE(w, -1e-12);
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR(d.interpolate(q, f), linear(q), 1e-12);
    EXPECT_NEAR(d.interpolate(loc, f), linear(q), 1e-12);
  }
  EXPECT_EQ(d.locate(Vec3(5, 5, 5)).tet, -1);
  EXPECT_THROW(d.interpolate(Vec3(5, 5, 5), f), std::out_of_range);
  EXPECT_THROW(d.interpolate(d.locate(Vec3(5, 5, 5)), f), std::out_of_range);
}

TEST(Domain, LocatingFromANearbyVertexFindsTheSameTet) {
  Domain d(random_points_in_ball(500, 1.0, 6));
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0.0, 0.02);
  for (int v = 0; v < static_cast<int>(d.num_vertices()); v += 5) {
    const Vec3 p = d.vertices()[v] + Vec3(jitter(rng), jitter(rng), jitter(rng));
    const Location expected = d.locate(p), found = d.locate(p, v);
    EXPECT_EQ(found.tet, expected.tet) << "near vertex " << v;
    if (found.tet < 0) continue;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(found.barycentric[i], expected.barycentric[i], 1e-12);
  }
  EXPECT_EQ(d.locate(Vec3(5, 5, 5), 0).tet, -1);
  EXPECT_THROW(d.locate(Vec3(0, 0, 0), static_cast<int>(d.num_vertices())), std::out_of_range);
}

TEST(Domain, InsertKeepsIndicesAndInterpolatesF) {
  Domain d(random_points_in_ball(300, 1.0, 6));
  std::vector<double> f;
  for (const Vec3& p : d.vertices()) f.push_back(p.x() + 2 * p.z());
  d.set_f(f);
  const std::vector<Vec3> before = d.vertices();
  const std::vector<Vec3> extra = random_points_in_ball(100, 0.6, 7);
  const std::vector<int> added = d.insert(extra);
  ASSERT_EQ(added.size(), extra.size());
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_EQ(d.vertices()[i], before[i]);
  for (std::size_t i = 0; i < added.size(); ++i) {
    EXPECT_EQ(d.vertices()[added[i]], extra[i]);
    EXPECT_NEAR(d.f()[added[i]], extra[i].x() + 2 * extra[i].z(), 1e-12);
  }
  // Re-inserting an existing vertex adds nothing.
  EXPECT_TRUE(d.insert({before[0]}).empty());
  EXPECT_THROW(d.insert({Vec3(9, 9, 9)}), std::invalid_argument);
}

TEST(Domain, MoveVerticesCarriesFOverByInterpolation) {
  Domain d(random_points_in_ball(400, 1.0, 8));
  std::vector<double> f;
  for (const Vec3& p : d.vertices()) f.push_back(1 - p.y());
  d.set_f(f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  std::vector<Vec3> moved = d.vertices();
  for (std::size_t i = 0; i < moved.size(); ++i)
    if (moved[i].norm() < 0.8) moved[i] += Vec3(jitter(rng), jitter(rng), jitter(rng));
  d.move_vertices(moved);
  EXPECT_EQ(d.vertices(), moved);
  for (std::size_t i = 0; i < moved.size(); ++i) EXPECT_NEAR(d.f()[i], 1 - moved[i].y(), 1e-12);
  const auto& v = d.vertices();
  for (const auto& t : d.tets()) EXPECT_GT(signed_volume(v[t[0]], v[t[1]], v[t[2]], v[t[3]]), 0);

  std::vector<Vec3> collapsed = d.vertices();
  collapsed[1] = collapsed[0];
  EXPECT_THROW(d.move_vertices(collapsed), std::invalid_argument);
}

// A move rebuilds the triangulation on all cores: the same Delaunay tets as a
// triangulation built one point after the other, with consistent neighbours,
// and the same arrays, bit for bit, on one thread and on two (on a lattice
// too, where the tets are only defined by CGAL's symbolic perturbation).
TEST(Domain, AMoveBuildsTheSameTetsAsASequentialTriangulationOnAnyThreads) {
  std::vector<Vec3> lattice;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k) lattice.emplace_back(0.1 * i, 0.1 * j, 0.1 * k);
  for (const std::vector<Vec3>& points : {random_points_in_ball(20000, 1.0, 21), lattice}) {
    const Domain before(points);
    std::vector<Vec3> positions = before.vertices();
    if (points.size() != lattice.size())
      for (std::size_t i = 0; i < positions.size(); i += 3) positions[i] *= 0.999;
    auto moved_on = [&](int threads) {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
      return before.moved(positions);
    };
    const Domain one = moved_on(1), two = moved_on(2);
    EXPECT_EQ(one.tets(), two.tets());
    EXPECT_EQ(one.tet_neighbors(), two.tet_neighbors());
    EXPECT_EQ(sorted(two.tets()), sorted(Domain(positions).tets()));
    const auto& tets = two.tets();
    const auto& nb = two.tet_neighbors();
    const auto& x = two.vertices();
    int hull_faces = 0;
    for (std::size_t t = 0; t < tets.size(); ++t) {
      EXPECT_GT(signed_volume(x[tets[t][0]], x[tets[t][1]], x[tets[t][2]], x[tets[t][3]]), 0);
      for (int i = 0; i < 4; ++i) {
        if (nb[t][i] < 0) {
          ++hull_faces;
          continue;
        }
        const auto& u = tets[nb[t][i]];
        int shared = 0;
        for (int k = 0; k < 4; ++k)
          if (k != i) shared += std::count(u.begin(), u.end(), tets[t][k]);
        EXPECT_EQ(shared, 3) << "tet " << t << " face " << i;
      }
    }
    EXPECT_GT(hull_faces, 0);
    // Point location restores the triangulation from the arrays.
    EXPECT_GE(two.locate(x[0] * 0.5 + x[1] * 0.5).tet, 0);
  }
}

// With its tets released (the optimizer's move), a domain still moves, the
// same as with them; its tets rebuilt are the same Delaunay tets, with their
// neighbours, and point location and interpolation work again.
TEST(Domain, ReleasedTetsMoveTheSameAndAreRebuiltTheSame) {
  Domain d = Domain::initial(test::sample_sphere(2000));
  std::vector<double> f;
  for (const Vec3& p : d.vertices()) f.push_back(p.squaredNorm() - 0.25);
  d.set_f(f);
  const Domain live = d;
  std::vector<Vec3> positions = d.vertices();
  for (std::size_t i = 0; i < positions.size(); i += 5)
    if (!d.on_boundary_sphere(static_cast<int>(i))) positions[i] *= 0.998;
  d.release_tets();
  EXPECT_EQ(d.num_tets(), 0u);
  EXPECT_EQ(d.vertices(), live.vertices());
  EXPECT_EQ(d.f(), live.f());
  const Domain moved = d.moved(positions, live.f()),
               moved_live = live.moved(positions, live.f());
  EXPECT_EQ(moved.tets(), moved_live.tets());
  EXPECT_EQ(moved.tet_neighbors(), moved_live.tet_neighbors());
  d.rebuild_tets();
  ASSERT_GT(d.num_tets(), 0u);
  EXPECT_EQ(sorted(d.tets()), sorted(live.tets()));
  const auto& tets = d.tets();
  const auto& nb = d.tet_neighbors();
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < 4; ++i) {
      if (nb[t][i] < 0) continue;
      const auto& u = tets[nb[t][i]];
      int shared = 0;
      for (int k = 0; k < 4; ++k)
        if (k != i) shared += std::count(u.begin(), u.end(), tets[t][k]);
      ASSERT_EQ(shared, 3) << "tet " << t << " face " << i;
    }
  const Vec3 q(0.1, -0.2, 0.3);
  EXPECT_NEAR(d.interpolate(q, d.f()), live.interpolate(q, live.f()), 1e-12);
}

TEST(Domain, CopyIsIndependent) {
  Domain a(random_points_in_ball(100, 1.0, 10));
  Domain b = a;
  b.insert({Vec3(0.01, 0.02, 0.03)});
  EXPECT_EQ(b.num_vertices(), a.num_vertices() + 1);
  EXPECT_EQ(a.mesh().tets, a.tets());
}

// A released triangulation comes back the same: the same tets found for the
// same points, with the same coordinates, and the same results from the moves
// and insertions that rebuild or change it (on a lattice too, where every
// cell is cospherical with its neighbours).
TEST(Domain, AReleasedTriangulationIsRestoredTheSame) {
  std::vector<Vec3> lattice;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) lattice.emplace_back(0.4 * i - 1, 0.4 * j - 1, 0.4 * k - 1);
  for (Domain d : {Domain::initial(test::sample_sphere(400)), Domain(lattice)}) {
    std::vector<double> f;
    for (const Vec3& p : d.vertices()) f.push_back(p.x() - 0.5 * p.y() * p.z());
    d.set_f(f);
    const Domain live = d;
    d.release_triangulation();
    EXPECT_TRUE(d.triangulation_released());
    EXPECT_EQ(d.tets(), live.tets());
    EXPECT_EQ(d.tet_neighbors(), live.tet_neighbors());
    const std::vector<Vec3> queries = random_points_in_ball(300, 0.9, 11);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const int near = static_cast<int>(i % d.num_vertices());
      for (const auto& [a, b] : {std::pair(d.locate(queries[i]), live.locate(queries[i])),
                                 std::pair(d.locate(queries[i], near), live.locate(queries[i], near))}) {
        EXPECT_EQ(a.tet, b.tet);
        EXPECT_EQ(a.barycentric, b.barycentric);
      }
    }
    // A released domain is located by a walk over its arrays: no
    // triangulation rebuilt, the same tets. Points on the tets' corners and
    // faces (ties) may land in another tet with them, but always in one that
    // contains them; points beyond the hull are outside.
    EXPECT_TRUE(d.triangulation_released());
    const auto& x = d.vertices();
    for (std::size_t v = 0; v < x.size(); v += 7) {
      const Vec3 mid = 0.5 * (x[v] + x[(v * 13 + 5) % x.size()]);
      for (const Vec3& p : {x[v], mid}) {
        const Location a = d.locate(p, static_cast<int>(v)), b = live.locate(p);
        ASSERT_EQ(a.tet >= 0, b.tet >= 0);
        if (a.tet < 0) continue;
        for (double w : a.barycentric) EXPECT_GE(w, -1e-12);
        EXPECT_NEAR(d.interpolate(a, f), live.interpolate(b, f), 1e-12);
      }
    }
    EXPECT_LT(d.locate(Vec3(0, 0, 2 * d.radius() + 5)).tet, 0);
    EXPECT_TRUE(d.triangulation_released());

    std::mt19937 rng(12);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    std::vector<Vec3> positions = d.vertices();
    for (std::size_t i = 0; i < positions.size(); ++i)
      if (!d.on_boundary_sphere(static_cast<int>(i)) && positions[i].norm() < 0.8)
        positions[i] += Vec3(jitter(rng), jitter(rng), jitter(rng));
    d.release_triangulation();
    const Domain moved = d.moved(positions), moved_live = live.moved(positions);
    EXPECT_EQ(moved.tets(), moved_live.tets());
    EXPECT_EQ(moved.f(), moved_live.f());

    // An insertion into the restored cells numbers the new tets in another
    // order, but they are the same tets, with the same vertices and f.
    Domain inserted = d, inserted_live = live;
    inserted.release_triangulation();
    const std::vector<Vec3> extra = random_points_in_ball(50, 0.7, 13);
    EXPECT_EQ(inserted.insert(extra), inserted_live.insert(extra));
    EXPECT_EQ(inserted.vertices(), inserted_live.vertices());
    EXPECT_EQ(inserted.f(), inserted_live.f());
    EXPECT_EQ(sorted(inserted.tets()), sorted(inserted_live.tets()));

    // Translated while released, and copied: located where the vertices now are.
    Domain translated = live, translated_live = live;
    translated.release_triangulation();
    const Vec3 offset(3e4, -2, 0.5);
    translated.translate(offset);
    translated_live.translate(offset);
    const Domain copy = translated;
    EXPECT_TRUE(copy.triangulation_released());
    EXPECT_TRUE(translated.triangulation_released());
    EXPECT_EQ(copy.vertices(), translated_live.vertices());
    for (const Vec3& q : queries) {
      EXPECT_EQ(translated.locate(q + offset).tet, translated_live.locate(q + offset).tet);
      EXPECT_EQ(copy.locate(q + offset).tet, translated_live.locate(q + offset).tet);
    }
  }
}

TEST(RadiusEdgeRatio, RegularTetIsSqrt6Over4) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(radius_edge_ratio(a, b, c, d), std::sqrt(6.0) / 4.0, 1e-14);
}

}  // namespace
}  // namespace pdd
