// Trimming to the samples' support, attributes carried to the output and
// unsupported components (contour.h).
#include <pdd/contour.h>
#include <pdd/quality.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "support/shapes.h"

namespace pdd {
namespace {

// The points of a Fibonacci sampling of the unit sphere for which `keep` holds.
template <typename Keep>
std::vector<Vec3> sphere_samples(int n, Keep keep) {
  std::vector<Vec3> kept;
  for (const Vec3& p : test::sample_sphere(n).points)
    if (keep(p)) kept.push_back(p);
  return kept;
}

TEST(Trim, AHemisphereSampledWithoutItsBaseGivesOneOpenPieceCutAtTheRim) {
  const TriangleMesh sphere = test::sphere_mesh(5);  // 8192 triangles, edge about 0.03
  const std::vector<Vec3> samples =
      sphere_samples(6000, [](const Vec3& p) { return p.z() > 0; });  // spacing about 0.04
  TriangleMesh mesh = sphere;
  TrimOptions options;
  options.distance = 2;
  const TrimReport r = trim_to_samples(mesh, samples, options);
  EXPECT_TRUE(r.trimmed);
  const SurfaceTopology topo = surface_topology(mesh);
  EXPECT_TRUE(topo.manifold);
  EXPECT_FALSE(topo.closed);
  EXPECT_EQ(topo.components, 1u);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(boundary_loops(mesh), 1);
  // About half the area goes; the rim lies within a few spacings below the equator.
  EXPECT_NEAR(r.area_removed, 0.5, 0.05);
  double lowest = 0;
  for (const Vec3& v : mesh.vertices) lowest = std::min(lowest, v.z());
  EXPECT_LT(lowest, -0.02);
  EXPECT_GT(lowest, -2.5 * r.spacing - 0.03);
  // Every vertex stays within the trim distance of a sample (with the slack of one edge).
  for (const Vec3& v : mesh.vertices) {
    double nearest = 1e9;
    for (const Vec3& s : samples) nearest = std::min(nearest, (v - s).norm());
    ASSERT_LT(nearest, 2 * 2 * r.spacing + 0.03);
  }
  // The cut makes no slivers: the share of triangles under 20 degrees stays small.
  const TriangleQuality before = triangle_quality(sphere);
  const TriangleQuality after = triangle_quality(mesh);
  std::cout << "min angle " << before.mean_min_angle << " -> " << after.mean_min_angle
            << ", under 20 degrees " << before.fraction_below_20 << " -> "
            << after.fraction_below_20 << "\n";
  EXPECT_GT(after.mean_min_angle, before.mean_min_angle - 2);
  EXPECT_LT(after.fraction_below_20, 0.01);
}

// The smallest angle (degrees) of each triangle with a boundary edge: the cut's rim.
std::vector<double> rim_min_angles(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) ++uses[std::minmax(f[i], f[(i + 1) % 3])];
  std::vector<double> angles;
  for (const auto& f : mesh.faces) {
    bool rim = false;
    for (int i = 0; i < 3; ++i) rim = rim || uses[std::minmax(f[i], f[(i + 1) % 3])] == 1;
    if (!rim) continue;
    double smallest = 180;
    for (int i = 0; i < 3; ++i) {
      const Vec3 u = mesh.vertices[f[(i + 1) % 3]] - mesh.vertices[f[i]];
      const Vec3 v = mesh.vertices[f[(i + 2) % 3]] - mesh.vertices[f[i]];
      smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / M_PI);
    }
    angles.push_back(smallest);
  }
  return angles;
}

// The triangles at the cut are as well shaped as the rest: a line through
// triangles leaves short edges and flat corners where it passes near a vertex,
// which the rim's remeshing removes. Cuts at several heights, so that the line
// meets the icosphere's vertices at every offset.
TEST(Trim, TheTrianglesAtTheCutKeepTheMeshQuality) {
  const TriangleMesh sphere = test::sphere_mesh(5);
  const TriangleQuality whole = triangle_quality(sphere);
  for (const double level : {-0.3, -0.1, 0.05, 0.2, 0.45}) {
    const std::vector<Vec3> samples =
        sphere_samples(6000, [&](const Vec3& p) { return p.z() > level; });
    TriangleMesh mesh = sphere;
    TrimOptions options;
    options.distance = 2;
    trim_to_samples(mesh, samples, options);
    const std::vector<double> rim = rim_min_angles(mesh);
    ASSERT_GT(rim.size(), 50u) << level;
    double mean = 0;
    int below_20 = 0;
    for (double a : rim) {
      mean += a / rim.size();
      below_20 += a < 20;
    }
    std::cout << "cut at z = " << level << ": " << rim.size() << " rim triangles, mean min angle "
              << mean << ", " << below_20 << " under 20 degrees (whole sphere: "
              << whole.mean_min_angle << ")\n";
    EXPECT_GT(mean, 38) << level;
    EXPECT_LE(below_20, 0.02 * rim.size()) << level;
    EXPECT_TRUE(surface_topology(mesh).manifold) << level;
    EXPECT_EQ(boundary_loops(mesh), 1) << level;
    double off = 0;
    for (const Vec3& v : mesh.vertices) off = std::max(off, std::abs(v.norm() - 1));
    EXPECT_LT(off, 0.1 * 0.03) << level;  // a tenth of the edge: on the sphere to second order
  }
}

TEST(Trim, ASmallHoleStaysClosedAndALargeOneOpens) {
  // Samples everywhere but a cap of angular radius 0.15 (about 4 spacings across ... 8).
  const std::vector<Vec3> samples =
      sphere_samples(8000, [](const Vec3& p) { return p.z() < std::cos(0.15); });
  TriangleMesh mesh = test::sphere_mesh(5);
  TrimOptions options;
  options.distance = 2;
  const TrimReport kept = trim_to_samples(mesh, samples, options);  // holes: 30 spacings
  EXPECT_TRUE(surface_topology(mesh).closed);
  EXPECT_EQ(kept.holes_kept, 1);
  EXPECT_EQ(kept.boundary_loops, 0);

  mesh = test::sphere_mesh(5);
  options.holes = 2;
  const TrimReport opened = trim_to_samples(mesh, samples, options);
  EXPECT_EQ(opened.holes_kept, 0);
  EXPECT_EQ(opened.boundary_loops, 1);
  EXPECT_TRUE(surface_topology(mesh).manifold);
}

// The distance from `p` to the nearest vertex of `mesh`.
double to_vertices(const TriangleMesh& mesh, const Vec3& p) {
  double nearest = 1e9;
  for (const Vec3& v : mesh.vertices) nearest = std::min(nearest, (v - p).norm());
  return nearest;
}

TEST(Trim, IslandsThatFewSamplesLieOnAreDroppedAndScannedOnesKept) {
  // Samples on the upper cap, on a small patch near the south pole (a few
  // dozen samples: scanned surface) and one lone sample on the equator's far
  // side (a stray's disc).
  std::vector<Vec3> samples = sphere_samples(
      8000, [](const Vec3& p) { return p.z() > 0.3 || (p - Vec3(0, 0, -1)).norm() < 0.08; });
  const Vec3 lone = Vec3(0, -1, -0.3).normalized();
  samples.push_back(lone);
  TrimOptions options;
  options.distance = 2;
  options.holes = 0;
  TriangleMesh all = test::sphere_mesh(5);
  options.islands = 0;
  trim_to_samples(all, samples, options);
  EXPECT_EQ(surface_topology(all).components, 3u);
  TriangleMesh mesh = test::sphere_mesh(5);
  options.islands = 15;  // both pieces are smaller: the samples on them decide
  const TrimReport r = trim_to_samples(mesh, samples, options);
  EXPECT_EQ(surface_topology(mesh).components, 2u);
  EXPECT_EQ(r.islands.components, 1);
  EXPECT_GT(r.islands.faces, 0);
  EXPECT_GT(to_vertices(mesh, lone), 0.3);             // the lone sample's disc went
  EXPECT_LT(to_vertices(mesh, Vec3(0, 0, -1)), 0.03);  // the patch stayed
}

// A hemisphere scanned with a few pairs of samples below its rim, each pair
// far from the rest (a scan's sparse edge): the trim keeps the surface under
// them, as the closed surface had it, instead of cutting it as an island.
TEST(Trim, SparseSamplesBeyondTheRimKeepTheirSurface) {
  std::vector<Vec3> samples = sphere_samples(6000, [](const Vec3& p) { return p.z() > 0; });
  std::vector<Vec3> sparse;
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3;
    for (const double da : {0.0, 0.03})
      sparse.push_back(Vec3(std::cos(a + da), std::sin(a + da), -0.6).normalized());
  }
  samples.insert(samples.end(), sparse.begin(), sparse.end());
  TriangleMesh mesh = test::sphere_mesh(5);
  TrimOptions options;
  options.distance = 2;
  const TrimReport r = trim_to_samples(mesh, samples, options);
  for (const Vec3& p : sparse) EXPECT_LT(to_vertices(mesh, p), 0.03);  // an edge
  EXPECT_EQ(r.islands.components, 0);
  EXPECT_EQ(surface_topology(mesh).components, 7u);
  EXPECT_TRUE(surface_topology(mesh).manifold);
}

TEST(Trim, OffLeavesTheMeshAndBadOptionsThrow) {
  TriangleMesh mesh = test::sphere_mesh(3);
  const std::size_t faces = mesh.faces.size();
  const std::vector<Vec3> samples = test::sample_sphere(500).points;
  EXPECT_FALSE(trim_to_samples(mesh, samples, {}).trimmed);
  EXPECT_EQ(mesh.faces.size(), faces);
  for (double bad : {-1.0, std::nan("")}) {
    TrimOptions o;
    o.distance = bad;
    EXPECT_THROW(trim_to_samples(mesh, samples, o), std::invalid_argument);
    o.distance = 2;
    o.holes = bad;
    EXPECT_THROW(trim_to_samples(mesh, samples, o), std::invalid_argument);
  }
}

TEST(Attributes, AColourRampComesOutAsAColourRamp) {
  PointSet samples = test::sample_sphere(4000);
  Attribute red{"red", "uchar", {}}, intensity{"intensity", "float", {}},
      label{"segment_index", "int", {}};
  for (const Vec3& p : samples.points) {
    red.values.push_back(std::round(127.5 * (p.z() + 1)));
    intensity.values.push_back(p.x());
    label.values.push_back(p.y() > 0 ? 7 : 3);
  }
  samples.attributes = {red, intensity, label};
  const TriangleMesh mesh = test::sphere_mesh(4);
  const std::vector<Attribute> out = interpolate_attributes(samples, mesh.vertices);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].name, "red");
  EXPECT_EQ(out[0].type, "uchar");
  double worst_red = 0, worst_intensity = 0;
  int wrong_labels = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    EXPECT_EQ(out[0].values[v], std::round(out[0].values[v]));  // uchar stays integral
    worst_red = std::max(worst_red, std::abs(out[0].values[v] - 127.5 * (p.z() + 1)));
    worst_intensity = std::max(worst_intensity, std::abs(out[1].values[v] - p.x()));
    const double l = out[2].values[v];
    EXPECT_TRUE(l == 7 || l == 3);  // labels are not averaged
    wrong_labels += std::abs(p.y()) > 0.05 && l != (p.y() > 0 ? 7 : 3);
  }
  EXPECT_LT(worst_red, 4);  // of 255
  EXPECT_LT(worst_intensity, 0.02);
  EXPECT_EQ(wrong_labels, 0);
}

TEST(Components, ThoseNearestToTooFewSamplesAreRemoved) {
  // A sphere and a small one beside it that only 3 samples support (a blob
  // around stray points), a third supported by 200, and a large bubble with
  // 15 samples, a hundredth of the others' density (around a cluster of strays).
  TriangleMesh mesh = test::sphere_mesh(3);
  auto add = [&](const TriangleMesh& part) {
    const int base = static_cast<int>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (auto f : part.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  };
  TriangleMesh blob = test::sphere_mesh(1, 0.1);
  for (Vec3& v : blob.vertices) v += Vec3(1.5, 0, 0);
  TriangleMesh part = test::sphere_mesh(2, 0.3);
  for (Vec3& v : part.vertices) v += Vec3(-2, 0, 0);
  TriangleMesh bubble = test::sphere_mesh(2, 0.5);  // 15 samples: enough, but too sparse
  for (Vec3& v : bubble.vertices) v += Vec3(0, 3, 0);
  add(blob);
  add(part);
  add(bubble);
  std::vector<Vec3> samples = test::sample_sphere(2000).points;
  for (const Vec3& p : test::sample_sphere(3, 0.1, Vec3(1.5, 0, 0)).points) samples.push_back(p);
  for (const Vec3& p : test::sample_sphere(200, 0.3, Vec3(-2, 0, 0)).points) samples.push_back(p);
  for (const Vec3& p : test::sample_sphere(15, 0.5, Vec3(0, 3, 0)).points) samples.push_back(p);
  const std::size_t faces = mesh.faces.size();
  const RemovedComponents r = remove_unsupported_components(mesh, samples, 10);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(static_cast<std::size_t>(r.faces), blob.faces.size() + bubble.faces.size());
  EXPECT_EQ(mesh.faces.size(), faces - blob.faces.size() - bubble.faces.size());
  EXPECT_EQ(surface_topology(mesh).components, 2u);
  for (const Vec3& v : mesh.vertices) {
    EXPECT_GT((v - Vec3(1.5, 0, 0)).norm(), 0.2);
    EXPECT_GT((v - Vec3(0, 3, 0)).norm(), 0.6);
  }
  EXPECT_THROW(remove_unsupported_components(mesh, samples, -1), std::invalid_argument);
}

}  // namespace
}  // namespace pdd
