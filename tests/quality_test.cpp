#include <gtest/gtest.h>
#include <pdd/io.h>
#include <pdd/errors.h>
#include <pdd/quality.h>
#include <pdd/report.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pdd {
namespace {

constexpr double kTol = 1e-9;

// The unit cube [0, 1]^3 as 12 outward triangles, shifted by `offset`.
TriangleMesh cube(const Vec3& offset = Vec3::Zero()) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(offset + Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Appends b to a.
void append(TriangleMesh& a, const TriangleMesh& b) {
  const int n = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) a.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
}

// A torus as an nu x nv quad grid, each quad split in two.
TriangleMesh torus(int nu, int nv) {
  TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.vertices.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u),
                              std::sin(v));
    }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& f : m.faces)
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6;
  return v;
}

TEST(TriangleAngles, KnownTriangles) {
  const auto equilateral =
      triangle_angles(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3) / 2, 0));
  for (const double a : equilateral) EXPECT_NEAR(a, 60.0, kTol);
  const auto right = triangle_angles(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR(right[0], 90.0, kTol);
  EXPECT_NEAR(right[1], 45.0, kTol);
  EXPECT_NEAR(right[2], 45.0, kTol);
  const auto flat = triangle_angles(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0));
  EXPECT_NEAR(flat[0], 0.0, kTol);
  EXPECT_NEAR(flat[1], 180.0, kTol);
  EXPECT_NEAR(flat[2], 0.0, kTol);
  const auto collapsed = triangle_angles(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(0, 0, 0));
  for (const double a : collapsed) EXPECT_EQ(a, 0.0);
}

TEST(TriangleQuality, StatisticsOfAHandMadeMesh) {
  // An equilateral triangle, a right isosceles one and a 5-degree sliver.
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0),
                Vec3(1, 0, 0),
                Vec3(0.5, std::sqrt(3) / 2, 0),
                Vec3(0, 1, 0),
                Vec3(0, 0, 2),
                Vec3(1, 0, 2),
                Vec3(std::cos(5 * M_PI / 180), std::sin(5 * M_PI / 180), 2)};
  m.faces = {{0, 1, 2}, {0, 1, 3}, {4, 5, 6}};
  const std::vector<double> smallest = min_angles(m);
  ASSERT_EQ(smallest.size(), 3u);
  EXPECT_NEAR(smallest[0], 60.0, kTol);
  EXPECT_NEAR(smallest[1], 45.0, kTol);
  EXPECT_NEAR(smallest[2], 5.0, kTol);  // the apex angle of the isosceles sliver

  const TriangleQuality q = triangle_quality(m);
  EXPECT_EQ(q.count, 3u);
  EXPECT_NEAR(q.min_angle, 5.0, kTol);
  EXPECT_NEAR(q.mean_min_angle, (60.0 + 45.0 + 5.0) / 3, kTol);
  EXPECT_NEAR(q.max_angle, 90.0, kTol);
  EXPECT_NEAR(q.fraction_below_10, 1.0 / 3, kTol);
  EXPECT_NEAR(q.fraction_below_20, 1.0 / 3, kTol);
  EXPECT_NEAR(q.fraction_below_30, 1.0 / 3, kTol);
  const Histogram& h = q.min_angle_histogram;
  EXPECT_EQ(h.lower, 0.0);
  EXPECT_EQ(h.bin_width, 5.0);
  EXPECT_EQ(h.upper(), 60.0);
  ASSERT_EQ(h.counts.size(), 12u);
  EXPECT_EQ(h.counts[1], 1u);   // 5 in [5, 10)
  EXPECT_EQ(h.counts[9], 1u);   // 45 in [45, 50)
  EXPECT_EQ(h.counts[11], 1u);  // 60 at the end goes to the last bin
}

TEST(TriangleQuality, EmptyMeshAndBadIndices) {
  const TriangleQuality q = triangle_quality(TriangleMesh{});
  EXPECT_EQ(q.count, 0u);
  EXPECT_EQ(q.mean_min_angle, 0.0);
  TriangleMesh bad = cube();
  bad.faces[3][1] = 8;
  EXPECT_THROW(triangle_quality(bad), std::invalid_argument);
  EXPECT_THROW(surface_topology(bad), std::invalid_argument);
}

TEST(Histogram, BinsAndClamping) {
  const Histogram h = histogram({-1.0, 0.0, 0.99, 1.0, 2.5, 3.0, 7.0, std::nan("")}, 0.0, 3.0, 3);
  EXPECT_EQ(h.counts, (std::vector<std::size_t>{3, 1, 3}));
  EXPECT_THROW(histogram({}, 1.0, 1.0, 3), std::invalid_argument);
}

TEST(TetQuality, RegularTetrahedron) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  for (const double angle : dihedral_angles(a, b, c, d))
    EXPECT_NEAR(angle, std::acos(1.0 / 3) * 180 / M_PI, kTol);
  TetMesh mesh{{a, b, c, d}, {{0, 1, 2, 3}}};
  if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(mesh.tets[0][2], mesh.tets[0][3]);
  const auto shapes = tet_shapes(mesh);
  ASSERT_EQ(shapes.size(), 1u);
  EXPECT_NEAR(shapes[0].min_dihedral, 70.528779365509308, 1e-9);
  EXPECT_NEAR(shapes[0].max_dihedral, 70.528779365509308, 1e-9);
  EXPECT_NEAR(shapes[0].radius_edge, std::sqrt(6.0) / 4, 1e-12);
}

TEST(TetQuality, CornerTetAndSliver) {
  // The corner tet of a cube: right angles at the three edges from the
  // corner, acos(1/sqrt(3)) at the three others.
  const auto corner = dihedral_angles(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  for (int k : {0, 1, 2}) EXPECT_NEAR(corner[k], 90.0, kTol);
  for (int k : {3, 4, 5}) EXPECT_NEAR(corner[k], std::acos(1 / std::sqrt(3.0)) * 180 / M_PI, kTol);

  // Two coincident corners: no angle is NaN.
  for (const double angle :
       dihedral_angles(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1))) {
    EXPECT_GE(angle, 0.0);
    EXPECT_LE(angle, 180.0);
  }

  // A sliver: four nearly coplanar points around a square.
  TetMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0),    Vec3(0, 1, 0),
                   Vec3(0, 0, 1), Vec3(0, 0, 0.02), Vec3(1, 1, 0.02)};
  mesh.tets = {{0, 1, 2, 3}, {4, 1, 2, 5}};
  for (auto& t : mesh.tets) {
    const auto& v = mesh.vertices;
    if ((v[t[1]] - v[t[0]]).dot((v[t[2]] - v[t[0]]).cross(v[t[3]] - v[t[0]])) < 0)
      std::swap(t[2], t[3]);
  }
  const TetQuality q = tet_quality(mesh);
  EXPECT_EQ(q.count, 2u);
  EXPECT_LT(q.min_dihedral, 10.0);
  EXPECT_GT(q.max_dihedral, 170.0);  // the sliver's dihedral angles approach 0 and 180
  EXPECT_NEAR(q.fraction_min_dihedral_below_10, 0.5, kTol);
  // The sliver's radius-edge ratio is excellent (its corners are nearly
  // cocircular): the reason to look at dihedral angles too.
  EXPECT_LT(q.min_radius_edge, 0.75);
  EXPECT_NEAR(q.max_radius_edge, std::sqrt(3.0) / 2, 1e-12);  // corner tet: R = sqrt(3)/2, edge 1
  std::size_t total = 0;
  for (const std::size_t n : q.dihedral_histogram.counts) total += n;
  EXPECT_EQ(total, 12u);
  EXPECT_EQ(q.dihedral_histogram.counts.size(), 18u);
  EXPECT_EQ(q.dihedral_histogram.counts[9], 3u);  // the corner tet's right angles, in [90, 100)
}

TEST(SurfaceTopology, CubeIsClosedGenusZero) {
  TriangleMesh m = cube();
  m.vertices.push_back(Vec3(5, 5, 5));  // unreferenced: not counted
  EXPECT_NEAR(signed_volume(m), 1.0, kTol);
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.vertices, 8u);
  EXPECT_EQ(s.edges, 18u);
  EXPECT_EQ(s.faces, 12u);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.boundary_edges, 0u);
  EXPECT_TRUE(s.edge_manifold);
  EXPECT_TRUE(s.manifold);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.genus, 0);
}

TEST(SurfaceTopology, TorusHasGenusOne) {
  const SurfaceTopology s = surface_topology(torus(12, 8));
  EXPECT_TRUE(s.closed && s.manifold);
  EXPECT_EQ(s.euler_characteristic, 0);
  EXPECT_EQ(s.genus, 1);
}

TEST(SurfaceTopology, OpenMeshReportsItsBoundary) {
  TriangleMesh m = cube();
  m.faces.pop_back();
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.boundary_edges, 3u);
  EXPECT_FALSE(s.closed);
  EXPECT_TRUE(s.edge_manifold);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.euler_characteristic, 1);
  EXPECT_EQ(s.genus, -1);
}

TEST(SurfaceTopology, TwoDisjointCubesAreTwoComponents) {
  TriangleMesh m = cube();
  append(m, cube(Vec3(3, 0, 0)));
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.components, 2u);
  EXPECT_EQ(s.euler_characteristic, 4);
  EXPECT_TRUE(s.closed && s.manifold);
  EXPECT_EQ(s.genus, 0);
}

TEST(SurfaceTopology, ThreeFacesOnOneEdgeAreNonManifold) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.non_manifold_edges, 1u);
  EXPECT_EQ(s.boundary_edges, 6u);
  EXPECT_FALSE(s.edge_manifold);
  EXPECT_FALSE(s.manifold);
  EXPECT_EQ(s.components, 1u);
}

TEST(SurfaceTopology, FlippedFaceIsInconsistent) {
  TriangleMesh m = cube();
  std::swap(m.faces[4][1], m.faces[4][2]);
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.inconsistent_edges, 3u);
  EXPECT_FALSE(s.edge_manifold);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.genus, -1);
}

TEST(SurfaceTopology, CubesSharingAVertexAreNotManifold) {
  // Cube 2 is moved so that its vertex 0 lands on cube 1's vertex 7, and its
  // faces are re-indexed to use that vertex.
  TriangleMesh m = cube();
  TriangleMesh other = cube(Vec3(1, 1, 1));
  const int n = static_cast<int>(m.vertices.size());
  for (int i = 1; i < 8; ++i) m.vertices.push_back(other.vertices[i]);
  for (const auto& f : other.faces) {
    std::array<int, 3> g;
    for (int k = 0; k < 3; ++k) g[k] = f[k] == 0 ? 7 : n + f[k] - 1;
    m.faces.push_back(g);
  }
  const SurfaceTopology s = surface_topology(m);
  EXPECT_TRUE(s.edge_manifold);
  EXPECT_EQ(s.non_manifold_vertices, 1u);
  EXPECT_FALSE(s.manifold);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.genus, -1);
}

// Angles of a mesh too large or too small for their squared lengths would
// come out as NaN: the report names the file instead.
TEST(QualityReport, RefusesMeshesOutOfTheMeasurableRange) {
  TriangleMesh m = cube();
  EXPECT_NE(quality_report("cube.ply", m, true).find("\"min_angle\": 45.000000"),
            std::string::npos);
  for (Vec3& v : m.vertices) v *= 1e200;
  try {
    quality_report("big.ply", m, false);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "big.ply: the vertices span 1.73e+200 (bounding-box diagonal), more than the "
              "1e+150 at which angles, areas and distances can be computed");
  }
  for (Vec3& v : m.vertices) v = v * 1e-180 * 1e-180;  // 1e-160 across
  EXPECT_THROW(quality_report("small.ply", m, true), InputError);
  // All at one point: degenerate, measured as such.
  for (Vec3& v : m.vertices) v = Vec3(1, 2, 3);
  EXPECT_NE(quality_report("point.ply", m, true).find("\"degenerate_faces\": 0"),
            std::string::npos);
}

TEST(SurfaceTopology, DegenerateFaceIsReported) {
  TriangleMesh m = cube();
  m.faces.push_back({0, 0, 1});
  const SurfaceTopology s = surface_topology(m);
  EXPECT_EQ(s.degenerate_faces, 1u);
  EXPECT_FALSE(s.edge_manifold);
}

// ------------------------------------------------------------ command line

struct CommandResult {
  int status;
  std::string out;
};

CommandResult run(const std::string& arguments) {
  const std::string command = std::string(PDD_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = pclose(pipe);
  return {WEXITSTATUS(status), out};
}

class QualityCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() / ("pdd_quality_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(QualityCommand, PrintsJsonForAClosedMesh) {
  TriangleMesh m = cube();
  append(m, cube(Vec3(3, 0, 0)));
  write_mesh(path("cubes.off"), m);
  const CommandResult r = run("quality --json " + path("cubes.off"));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 24"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"components\": 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"euler_characteristic\": 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"closed\": true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"genus\": 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"min_angle\": 45.000000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"counts\": [0, 0, 0, 0, 0, 0, 0, 0, 0, 24, 0, 0]"), std::string::npos)
      << r.out;
}

TEST_F(QualityCommand, PrintsTextForAnOpenMesh) {
  TriangleMesh m = cube();
  m.faces.pop_back();
  write_mesh(path("open.ply"), m);
  const CommandResult r = run("quality " + path("open.ply"));
  ASSERT_EQ(r.status, 0) << r.out;
  std::istringstream lines(r.out);
  bool boundary = false, closed = false, genus = false;
  for (std::string line; std::getline(lines, line);) {
    boundary |=
        line.find("boundary edges") != std::string::npos && line.find(" 3") != std::string::npos;
    closed |= line.find("closed") != std::string::npos && line.find("no") != std::string::npos;
    genus |= line.find("genus") != std::string::npos && line.find("n/a") != std::string::npos;
  }
  EXPECT_TRUE(boundary && closed && genus) << r.out;
}

TEST_F(QualityCommand, BadFileIsAnInputError) {
  std::ofstream(path("broken.off")) << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  const CommandResult r = run("quality " + path("broken.off"));
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("broken.off"), std::string::npos) << r.out;
  EXPECT_EQ(run("quality " + path("missing.ply")).status, 2);
}

}  // namespace
}  // namespace pdd
