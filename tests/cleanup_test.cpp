#include <gtest/gtest.h>
#include <pdd/contour.h>
#include <pdd/domain.h>
#include <pdd/quality.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/figure2_layouts.h"

namespace pdd {
namespace {

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& f : m.faces)
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

double max_sphere_deviation(const TriangleMesh& m) {
  double worst = 0;
  for (const Vec3& v : m.vertices) worst = std::max(worst, std::abs(v.norm() - 1.0));
  return worst;
}

// The isosurface of the random two-layer domain of Figure 2(b): crossings at
// the midpoints, but caps and needles from the irregular tets.
TriangleMesh rough_sphere() {
  const Domain d = test::figure2_domain(test::Figure2Layout::kUnbiasedRandom, 600, 3);
  return marching_tetrahedra(d.mesh(), d.f()).mesh;
}

TEST(Cleanup, FewerBadTrianglesSameTopologyAndShape) {
  TriangleMesh mesh = rough_sphere();
  const TriangleQuality before = triangle_quality(mesh);
  const SurfaceTopology topology_before = surface_topology(mesh);
  const double volume_before = signed_volume(mesh);
  const double deviation_before = max_sphere_deviation(mesh);

  const CleanupReport report = cleanup_isosurface(mesh);
  const TriangleQuality after = triangle_quality(mesh);
  const SurfaceTopology topology_after = surface_topology(mesh);
  std::cout << report.flips << " flips, " << report.collapses << " collapses; under 20 deg "
            << before.fraction_below_20 << " -> " << after.fraction_below_20 << ", mean min angle "
            << before.mean_min_angle << " -> " << after.mean_min_angle << "\n";
  EXPECT_GT(report.flips, 0);
  EXPECT_GT(report.collapses, 0);
  EXPECT_LT(after.fraction_below_20, 0.5 * before.fraction_below_20);
  EXPECT_GT(after.mean_min_angle, before.mean_min_angle + 2.0);

  EXPECT_TRUE(topology_after.closed);
  EXPECT_TRUE(topology_after.manifold);
  EXPECT_EQ(topology_after.components, topology_before.components);
  EXPECT_EQ(topology_after.euler_characteristic, topology_before.euler_characteristic);
  // Still facing outwards and the same solid: flips and collapses where the
  // surface is nearly flat barely move it.
  EXPECT_NEAR(signed_volume(mesh), volume_before, 0.005 * volume_before);
  EXPECT_LE(max_sphere_deviation(mesh), deviation_before + 0.01);
  EXPECT_EQ(mesh.faces.size(), 2 * mesh.vertices.size() - 4);  // a closed genus-0 surface
}

// The relaxation (vertices toward their neighbours' centroid, lifted onto a
// fitted quadric) takes the triangles toward equilateral and keeps the
// vertices on the sphere to second order: against flips and collapses alone.
TEST(Cleanup, RelaxingTheVerticesRaisesTheAnglesAndKeepsTheSphere) {
  TriangleMesh relaxed = rough_sphere(), unrelaxed = relaxed;
  const double mean_deviation_before = [&] {
    double sum = 0;
    for (const Vec3& v : relaxed.vertices) sum += std::abs(v.norm() - 1.0);
    return sum / relaxed.vertices.size();
  }();
  CleanupOptions without;
  without.relax_rounds = 0;
  cleanup_isosurface(unrelaxed, without);
  const CleanupReport report = cleanup_isosurface(relaxed);
  const TriangleQuality a = triangle_quality(unrelaxed), b = triangle_quality(relaxed);
  std::cout << report.moves << " moves; mean min angle " << a.mean_min_angle << " -> "
            << b.mean_min_angle << ", under 20 deg " << a.fraction_below_20 << " -> "
            << b.fraction_below_20 << "\n";
  EXPECT_GT(report.moves, static_cast<int>(relaxed.vertices.size()) / 2);
  EXPECT_GT(b.mean_min_angle, 45.0);
  EXPECT_GT(b.mean_min_angle, a.mean_min_angle + 3.0);
  EXPECT_LE(b.fraction_below_20, a.fraction_below_20);
  const SurfaceTopology topology = surface_topology(relaxed);
  EXPECT_TRUE(topology.closed && topology.manifold);
  EXPECT_EQ(topology.euler_characteristic, 2);
  double sum = 0;
  for (const Vec3& v : relaxed.vertices) sum += std::abs(v.norm() - 1.0);
  EXPECT_LT(sum / relaxed.vertices.size(), 1.5 * mean_deviation_before + 1e-3);
  EXPECT_LE(max_sphere_deviation(relaxed), max_sphere_deviation(unrelaxed) + 0.005);

  TriangleMesh m = rough_sphere();
  CleanupOptions bad;
  bad.relax_rounds = -1;
  EXPECT_THROW(cleanup_isosurface(m, bad), std::invalid_argument);
}

// Two triangles of a unit square split along the diagonal that leaves two
// right angles opposite it (not Delaunay when the square is squashed).
TriangleMesh squashed_pair(double fold_height) {
  TriangleMesh m;
  // a (0,0), b (4,1): the shared edge; c above it, d below it.
  m.vertices = {Vec3(0, 0, 0), Vec3(4, 1, 0), Vec3(1, 2, 0), Vec3(3, -1, fold_height)};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  return m;
}

TEST(Cleanup, FlipsTheLongDiagonalOfAFlatPair) {
  TriangleMesh m = squashed_pair(0.0);
  const double before = triangle_quality(m).min_angle;
  const CleanupReport report = cleanup_isosurface(m);
  EXPECT_EQ(report.flips, 1);
  EXPECT_GT(triangle_quality(m).min_angle, before);
  // The new diagonal joins c and d, and both faces still point along +z.
  for (const auto& f : m.faces) {
    EXPECT_TRUE(std::count(f.begin(), f.end(), 2) && std::count(f.begin(), f.end(), 3));
    const Vec3 n = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
    EXPECT_GT(n.z(), 0);
  }
}

TEST(Cleanup, LeavesAFoldAlone) {
  TriangleMesh m = squashed_pair(2.0);  // the normals differ by about 50 degrees
  const auto faces = m.faces;
  const CleanupReport report = cleanup_isosurface(m);
  EXPECT_EQ(report.flips, 0);
  EXPECT_EQ(m.faces, faces);
}

// A cap (c just off the middle of ab) folded 45 degrees against its
// neighbour: not flat, but flipping ab to cd moves the surface by less than a
// tenth of ab, so the flip is made (and not with max_deviation 0).
TEST(Cleanup, FlipsACapOnACreaseWhenThatBarelyMovesTheSurface) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0.1, 0), Vec3(2, -2, 2)};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  TriangleMesh kept = m;
  CleanupOptions strict;
  strict.max_deviation = 0;
  EXPECT_EQ(cleanup_isosurface(kept, strict).flips, 0);
  EXPECT_EQ(cleanup_isosurface(m).flips, 1);
  EXPECT_GT(triangle_quality(m).min_angle, 10 * triangle_quality(kept).min_angle);
  for (const auto& f : m.faces)
    EXPECT_TRUE(std::count(f.begin(), f.end(), 2) && std::count(f.begin(), f.end(), 3));

  CleanupOptions bad;
  bad.max_deviation = -0.1;
  EXPECT_THROW(cleanup_isosurface(m, bad), std::invalid_argument);
}

// No relaxation, a 2-degree dihedral bound and no small moves past it.
CleanupOptions collapses_within_2_degrees() {
  CleanupOptions options;
  options.relax_rounds = 0;
  options.max_deviation = 0;
  options.max_dihedral_degrees = 2;
  return options;
}

// A needle (u, v, c) = vertices 0, 1, 2 with u's other triangles rising to
// (0, 0.6, lift) and v's tilted 20 degrees down.
TriangleMesh needle_fan(double lift) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0.1, 0),         Vec3(0, 0, 0),       Vec3(0.5, 0.05, 0),
                Vec3(0, 0.6, lift),      Vec3(-0.5, 0.05, 0), Vec3(0.3, -0.4, -0.146),
                Vec3(-0.3, -0.4, -0.146)};
  m.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {1, 4, 6}, {1, 6, 5}, {1, 5, 2}};
  return m;
}

// A needle (u, v, c) = vertices 0, 1, 2, u and v 0.1 apart, whose far corner c
// has valence three inside the tall triangle (u, v, x = (0.05, 3, 0)); the
// triangles beyond uv are folded up, vx and xu are on the border.
TriangleMesh needle_at_valence_three_corner(const Vec3& c) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0),    Vec3(0.1, 0, 0),  c, Vec3(0.05, 3, 0), Vec3(0.05, -1, 2),
                Vec3(1, -0.5, 2), Vec3(-1, -0.5, 2)};
  m.faces = {{0, 1, 2}, {1, 3, 2}, {3, 0, 2}, {1, 0, 4}, {1, 4, 5}, {0, 6, 4}};
  return m;
}

// Collapsing uv breaks the link condition (x is a third common neighbour),
// so c is removed and its three triangles become one; no flip reaches c.
TEST(Cleanup, RemovesAValenceThreeCornerThatBlocksANeedlesCollapse) {
  const Vec3 c(0.05, 1, 0);
  TriangleMesh m = needle_at_valence_three_corner(c);
  CleanupOptions options;
  options.relax_rounds = 0;
  const CleanupReport report = cleanup_isosurface(m, options);
  EXPECT_EQ(report.collapses, 1);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.faces.size(), 4u);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), c), 0);
  const SurfaceTopology topology = surface_topology(m);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.euler_characteristic, 1);  // still a disc
}

// A needle (u, v, c) and its neighbour (v, u, d) on a plane, v's other
// triangles tilted 20 degrees down. Under a 2-degree bound, moving v to the
// midpoint of uv turns them too far, but moving u onto v turns nothing: the
// edge is collapsed to v's end.
TEST(Cleanup, CollapsesANeedleToTheEndThatKeepsItsNeighboursWhenTheMidpointWouldTurnThem) {
  TriangleMesh m = needle_fan(0);
  const Vec3 u = m.vertices[0], v = m.vertices[1];
  const CleanupReport report = cleanup_isosurface(m, collapses_within_2_degrees());
  EXPECT_EQ(report.collapses, 1);
  EXPECT_EQ(report.flips, 0);
  EXPECT_EQ(m.faces.size(), 5u);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), v), 1);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), u), 0);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), 0.5 * (u + v)), 0);
  EXPECT_EQ(surface_topology(m).euler_characteristic, 1);
}

// The same needle with u's triangles tilted up: under a 2-degree bound no
// collapse keeps every neighbour, but the midpoint moves u and v by 0.05,
// under 0.15 of the needle's longest edge (0.5), and folds nothing: the
// collapse is made, and not with max_deviation 0.
TEST(Cleanup, CollapsesANeedleWhoseEndsMoveLittleHoweverItsNeighboursTurn) {
  TriangleMesh m = needle_fan(0.3);
  const Vec3 u = m.vertices[0], v = m.vertices[1];
  CleanupOptions options = collapses_within_2_degrees();
  TriangleMesh kept = m;
  EXPECT_EQ(cleanup_isosurface(kept, options).collapses, 0);
  EXPECT_EQ(kept.vertices.size(), 7u);

  options.max_deviation = 0.15;
  EXPECT_EQ(cleanup_isosurface(m, options).collapses, 1);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), 0.5 * (u + v)), 1);
  const SurfaceTopology topology = surface_topology(m);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.euler_characteristic, 1);
}

// The valence-three corner c of the needle (u, v, c) lifted 0.1 off the
// triangle (u, v, x) that its removal leaves: its thin triangles (v, x, c)
// and (x, u, c) turn about 70 degrees from it, over the dihedral bound, but c
// lies within 0.15 of that triangle's longest edge (3) from it: removed by
// default, kept with max_deviation 0.
TEST(Cleanup, RemovesALowValenceThreeSpikeHoweverItsTrianglesTurn) {
  const Vec3 c(0.05, 1, 0.1);
  TriangleMesh m = needle_at_valence_three_corner(c);
  CleanupOptions options;
  options.relax_rounds = 0;
  options.max_deviation = 0;
  TriangleMesh kept = m;
  cleanup_isosurface(kept, options);
  EXPECT_EQ(std::count(kept.vertices.begin(), kept.vertices.end(), c), 1);

  options.max_deviation = CleanupOptions().max_deviation;
  EXPECT_EQ(cleanup_isosurface(m, options).collapses, 1);
  EXPECT_EQ(std::count(m.vertices.begin(), m.vertices.end(), c), 0);
  EXPECT_EQ(m.faces.size(), 4u);
  EXPECT_EQ(surface_topology(m).euler_characteristic, 1);
}

TEST(Cleanup, RejectsBadInput) {
  TriangleMesh m = squashed_pair(0.0);
  CleanupOptions o;
  o.max_dihedral_degrees = 90;
  EXPECT_THROW(cleanup_isosurface(m, o), std::invalid_argument);
  o = CleanupOptions();
  o.needle_angle_degrees = -1;
  EXPECT_THROW(cleanup_isosurface(m, o), std::invalid_argument);
  // The second face repeats the first one's orientation on the shared edge.
  m.faces[1] = {0, 1, 3};
  EXPECT_THROW(cleanup_isosurface(m), std::invalid_argument);
}

}  // namespace
}  // namespace pdd
