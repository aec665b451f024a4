#include <pdd/domain.h>

#include <gtest/gtest.h>

#include <random>

namespace pdd {
namespace {

PointSet random_ball(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  PointSet ps;
  for (int i = 0; i < n; ++i) ps.points.push_back(Vec3(g(rng), g(rng), g(rng)).normalized());
  return ps;
}

TEST(InitialDomain, MeetsRadiusEdgeBoundAndContainsInput) {
  const PointSet input = random_ball(500, 1);
  RefinementReport report;
  const Domain d = Domain::initial(input, {}, &report);
  std::cout << "vertices " << d.num_vertices() << " tets " << d.num_tets() << " interior "
            << report.inserted_interior << " boundary " << report.inserted_boundary
            << " skipped " << report.skipped << " worst " << report.worst_radius_edge << "\n";
  EXPECT_LE(report.worst_radius_edge, 1.3 + 1e-9);
  for (const Vec3& p : input.points) EXPECT_GE(d.locate(p).tet, 0);
}

}  // namespace
}  // namespace pdd
