// The cut of handles the samples contradict (contour.h, cut_unsupported_handles).
#include <gtest/gtest.h>
#include <pdd/contour.h>
#include <pdd/quality.h>

#include <cmath>

#include "support/shapes.h"

namespace pdd {
namespace {

// A torus around the z axis (major radius R, minor r) as an nu x nv grid of
// quads split in two, outward-facing.
TriangleMesh torus_mesh(double R, double r, int nu, int nv) {
  TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      const Vec3 radial(std::cos(u), std::sin(u), 0);
      m.vertices.push_back(R * radial + r * (std::cos(v) * radial + Vec3(0, 0, std::sin(v))));
    }
  const auto at = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// Points on the disc z = 0 of radius `radius`, normals +z, on a square grid of `step`.
void add_lid(PointSet& ps, double radius, double step) {
  for (double x = -radius; x <= radius; x += step)
    for (double y = -radius; y <= radius; y += step)
      if (std::hypot(x, y) <= radius) {
        ps.points.emplace_back(x, y, 0);
        ps.normals.emplace_back(0, 0, 1);
      }
}

constexpr double kR = 0.5, kr = 0.35;  // a fat torus: its hole is 0.15 wide

SurfaceTopology topology(const TriangleMesh& m) { return surface_topology(m); }

TEST(Handles, ATunnelThroughAWallTheSamplesCloseIsCutAndCapped) {
  TriangleMesh mesh = torus_mesh(kR, kr, 96, 64);
  ASSERT_EQ(topology(mesh).genus, 1);
  // The samples: the torus but around its inner equator, and a wall across
  // its hole: the truth is a solid with no tunnel there.
  PointSet samples;
  const PointSet torus = test::sample_torus(20000, kR, kr);
  for (std::size_t i = 0; i < torus.size(); ++i) {
    const Vec3& p = torus.points[i];
    if (std::hypot(p.x(), p.y()) < kR && std::abs(p.z()) < 0.5 * kr) continue;
    samples.points.push_back(p);
    samples.normals.push_back(torus.normals[i]);
  }
  add_lid(samples, kR - 0.6 * kr, 0.01);
  const CutHandles cut = cut_unsupported_handles(mesh, samples);
  EXPECT_EQ(cut.handles, 1);
  EXPECT_GT(cut.faces, 0);
  const SurfaceTopology t = topology(mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  // The caps span the hole near the wall (z = 0) and stay inside the torus's extent.
  for (const Vec3& v : mesh.vertices) EXPECT_LE(std::hypot(v.x(), v.y()), kR + kr + 1e-9);
}

TEST(Handles, AHandleTheSamplesSupportStays) {
  TriangleMesh mesh = torus_mesh(kR, kr, 96, 64);
  const TriangleMesh before = mesh;
  const CutHandles cut = cut_unsupported_handles(mesh, test::sample_torus(20000, kR, kr));
  EXPECT_EQ(cut.handles, 0);
  EXPECT_EQ(mesh.faces.size(), before.faces.size());
  EXPECT_EQ(topology(mesh).genus, 1);
}

TEST(Handles, AWaistThatSeparatesIsNotCut) {
  // An elongated ellipsoid whose waist crosses a wall of samples: cutting it
  // would split the surface in two, so it is a limb, not a handle.
  const Vec3 axes(1.5, 0.3, 0.3);
  TriangleMesh mesh = test::sphere_mesh(5);
  for (Vec3& v : mesh.vertices) v = v.cwiseProduct(axes);
  PointSet samples;
  const PointSet e = test::sample_ellipsoid(20000, axes);
  for (std::size_t i = 0; i < e.size(); ++i)
    if (std::abs(e.points[i].x()) > 0.2) {
      samples.points.push_back(e.points[i]);
      samples.normals.push_back(e.normals[i]);
    }
  for (double x = -0.08; x <= 0.08; x += 0.04)  // a wall, five layers thick
    for (double y = -0.3; y <= 0.3; y += 0.01)
      for (double z = -0.3; z <= 0.3; z += 0.01) {
        samples.points.emplace_back(x, y, z);
        samples.normals.emplace_back(1, 0, 0);
      }
  const std::size_t faces = mesh.faces.size();
  EXPECT_EQ(cut_unsupported_handles(mesh, samples).handles, 0);
  EXPECT_EQ(mesh.faces.size(), faces);
  EXPECT_EQ(topology(mesh).components, 1);
}

TEST(Handles, AWaistOfThreeEdgesIsCutAndBothSidesClosed) {
  // A torus whose minor circle has three vertices: each meridian is a cycle of
  // three edges that bounds no face and does not separate; one cut leaves a
  // sphere, on which every other meridian separates.
  TriangleMesh mesh = torus_mesh(kR, kr, 12, 3);
  ASSERT_EQ(topology(mesh).genus, 1);
  const std::size_t faces = mesh.faces.size();
  EXPECT_EQ(cut_triangle_waists(mesh), 1);
  EXPECT_EQ(mesh.faces.size(), faces + 2);
  const SurfaceTopology t = topology(mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  TriangleMesh sphere = test::sphere_mesh(3);
  const std::size_t sphere_faces = sphere.faces.size();
  EXPECT_EQ(cut_triangle_waists(sphere), 0);
  EXPECT_EQ(sphere.faces.size(), sphere_faces);
}

TEST(Handles, WaistsOfTwoToriAreEachCutOnce) {
  // Three such tori side by side: one cut each, in one pass, and no more (every other meridian
  // then separates its own torus).
  TriangleMesh mesh;
  for (int t = 0; t < 3; ++t) {
    const TriangleMesh one = torus_mesh(kR, kr, 12 + t, 3);
    const int base = static_cast<int>(mesh.vertices.size());
    for (const Vec3& p : one.vertices) mesh.vertices.push_back(p + Vec3(2.0 * t, 0, 0));
    for (const auto& f : one.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  ASSERT_EQ(topology(mesh).components, 3);
  EXPECT_EQ(cut_triangle_waists(mesh), 3);
  const SurfaceTopology t = topology(mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.components, 3);
  EXPECT_EQ(t.genus, 0);
}

TEST(Handles, OffOrWithoutNormalsNothingHappensAndBadOptionsThrow) {
  TriangleMesh mesh = torus_mesh(kR, kr, 48, 32);
  PointSet bare = test::sample_torus(2000, kR, kr);
  bare.normals.clear();
  EXPECT_EQ(cut_unsupported_handles(mesh, bare).handles, 0);
  HandleOptions off;
  off.enabled = false;
  EXPECT_EQ(cut_unsupported_handles(mesh, test::sample_torus(2000, kR, kr), off).handles, 0);
  HandleOptions bad;
  bad.support_degrees = 90;
  EXPECT_THROW(cut_unsupported_handles(mesh, bare, bad), std::invalid_argument);
  bad = {};
  bad.band_rings = 0;
  EXPECT_THROW(cut_unsupported_handles(mesh, bare, bad), std::invalid_argument);
}

}  // namespace
}  // namespace pdd
