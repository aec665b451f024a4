#include <gtest/gtest.h>
#include <pdd/contour.h>
#include <pdd/domain.h>
#include <pdd/quality.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "support/figure2_layouts.h"

namespace pdd {
namespace {

// Grid points of spacing h over [lo, hi] (per axis), each moved by up to
// jitter * h along every axis.
std::vector<Vec3> grid_points(const Vec3& lo, const Vec3& hi, double h, double jitter,
                              unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * h, jitter * h);
  std::vector<Vec3> points;
  for (double x = lo.x(); x <= hi.x() + 1e-9; x += h)
    for (double y = lo.y(); y <= hi.y() + 1e-9; y += h)
      for (double z = lo.z(); z <= hi.z() + 1e-9; z += h) {
        const Vec3 p(x, y, z);
        points.push_back(jitter > 0 ? Vec3(p + Vec3(u(rng), u(rng), u(rng))) : p);
      }
  return points;
}

template <typename F>
std::vector<double> sample(const std::vector<Vec3>& vertices, F f) {
  std::vector<double> values;
  for (const Vec3& p : vertices) values.push_back(f(p));
  return values;
}

double unit_sphere(const Vec3& p) { return p.norm() - 1.0; }

// Signed volume enclosed by a closed, consistently oriented mesh.
double enclosed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& f : m.faces)
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

Vec3 face_normal(const TriangleMesh& m, int face) {
  const auto& f = m.faces[face];
  return (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
}

// Gradient of the linear interpolant of f over tet t.
Vec3 tet_gradient(const TetMesh& mesh, const std::vector<double>& f, int t) {
  const auto& tet = mesh.tets[t];
  Eigen::Matrix3d e;
  Vec3 df;
  for (int i = 0; i < 3; ++i) {
    e.row(i) = (mesh.vertices[tet[i + 1]] - mesh.vertices[tet[0]]).transpose();
    df[i] = f[tet[i + 1]] - f[tet[0]];
  }
  return e.partialPivLu().solve(df);
}

bool tet_changes_sign(const std::array<int, 4>& tet, const std::vector<double>& f) {
  int negatives = 0;
  for (int v : tet) negatives += f[v] < 0;
  return negatives > 0 && negatives < 4;
}

// A jittered grid domain around the unit sphere, shared by several tests.
const TetMesh& sphere_domain() {
  static const TetMesh mesh =
      Domain(grid_points(Vec3::Constant(-1.3), Vec3::Constant(1.3), 0.1, 0.25, 7)).mesh();
  return mesh;
}

TEST(MarchingTetrahedra, SphereIsClosedManifoldWithEulerCharacteristicTwo) {
  const TetMesh& mesh = sphere_domain();
  const auto f = sample(mesh.vertices, unit_sphere);
  const IsoSurface s = marching_tetrahedra(mesh, f);
  const SurfaceTopology topology = surface_topology(s.mesh);
  EXPECT_TRUE(topology.closed);
  EXPECT_TRUE(topology.edge_manifold);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.components, 1u);
  EXPECT_EQ(topology.euler_characteristic, 2);
  EXPECT_EQ(topology.genus, 0);
  EXPECT_EQ(topology.vertices, s.mesh.vertices.size());  // no unreferenced isovertex

  // One isovertex per crossing edge, one face per 1/3 tet and two per 2/2 tet.
  std::set<std::array<int, 2>> crossing_edges;
  std::size_t expected_faces = 0;
  for (const auto& tet : mesh.tets) {
    int negatives = 0;
    for (int i = 0; i < 4; ++i) {
      negatives += f[tet[i]] < 0;
      for (int j = i + 1; j < 4; ++j)
        if ((f[tet[i]] < 0) != (f[tet[j]] < 0))
          crossing_edges.insert({std::min(tet[i], tet[j]), std::max(tet[i], tet[j])});
    }
    expected_faces += negatives == 2 ? 2 : (negatives == 1 || negatives == 3) ? 1 : 0;
  }
  EXPECT_EQ(s.mesh.vertices.size(), crossing_edges.size());
  EXPECT_EQ(s.mesh.faces.size(), expected_faces);
  const std::set<std::array<int, 2>> isovertex_edges(s.vertex_edge.begin(), s.vertex_edge.end());
  EXPECT_EQ(isovertex_edges, crossing_edges);
}

TEST(MarchingTetrahedra, IsoverticesAreWithinTheInterpolationErrorOfTheSphere) {
  const TetMesh& mesh = sphere_domain();
  const auto f = sample(mesh.vertices, unit_sphere);
  const IsoSurface s = marching_tetrahedra(mesh, f);
  ASSERT_EQ(s.vertex_edge.size(), s.mesh.vertices.size());
  for (std::size_t i = 0; i < s.mesh.vertices.size(); ++i) {
    const auto [a, b] = s.vertex_edge[i];
    ASSERT_LT(a, b);
    const Vec3 &pa = mesh.vertices[a], &pb = mesh.vertices[b], &p = s.mesh.vertices[i];
    // On the edge, where the linear interpolant of f vanishes.
    const double length = (pb - pa).norm();
    const double t = (p - pa).dot(pb - pa) / (length * length);
    EXPECT_LT((pa + t * (pb - pa) - p).norm(), 1e-12);
    EXPECT_NEAR((1 - t) * f[a] + t * f[b], 0.0, 1e-12);
    // |x| - 1 is convex with second derivative at most 1/|x| along any line,
    // so on an edge of length L whose closest point to the origin is at
    // distance r, the zero of the interpolant lies inside the sphere and at
    // most L^2 / (8 r) from it (1 - |p| is the distance).
    const double s_closest = std::clamp(-pa.dot(pb - pa) / (length * length), 0.0, 1.0);
    const double r = (pa + s_closest * (pb - pa)).norm();
    EXPECT_LE(p.norm(), 1.0 + 1e-12);
    EXPECT_LE(1.0 - p.norm(), length * length / (8 * r) + 1e-12);
  }
}

TEST(MarchingTetrahedra, FacesPointOutwardAlongTheGradient) {
  const TetMesh& mesh = sphere_domain();
  const auto f = sample(mesh.vertices, unit_sphere);
  const IsoSurface s = marching_tetrahedra(mesh, f);
  // The faces lie in the unit ball (their vertices do), so the volume is at
  // most 4 pi / 3. Every face point is a convex combination of isovertices
  // with |v| >= rho that are pairwise within D (the largest crossing tet
  // edge), so its squared norm is at least rho^2 - D^2 / 2: the surface
  // encloses the ball of that radius.
  double rho = 1, diameter = 0;
  for (const Vec3& p : s.mesh.vertices) rho = std::min(rho, p.norm());
  for (const int t : s.facet_tet)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        diameter = std::max(
            diameter, (mesh.vertices[mesh.tets[t][i]] - mesh.vertices[mesh.tets[t][j]]).norm());
  const double volume = enclosed_volume(s.mesh);
  EXPECT_LE(volume, 4 * M_PI / 3);
  EXPECT_GE(volume, 4 * M_PI / 3 * std::pow(rho * rho - diameter * diameter / 2, 1.5));
  for (std::size_t i = 0; i < s.mesh.faces.size(); ++i) {
    const Vec3 n = face_normal(s.mesh, static_cast<int>(i));
    const Vec3 g = tet_gradient(mesh, f, s.facet_tet[i]);
    EXPECT_GT(n.dot(g), 0.0) << "face " << i;
  }
}

TEST(MarchingTetrahedra, FacetTetsChangeSignAndHoldTheFacetVertices) {
  const TetMesh& mesh = sphere_domain();
  const auto f = sample(mesh.vertices, unit_sphere);
  const IsoSurface s = marching_tetrahedra(mesh, f);
  ASSERT_EQ(s.facet_tet.size(), s.mesh.faces.size());
  for (std::size_t i = 0; i < s.mesh.faces.size(); ++i) {
    const int t = s.facet_tet[i];
    ASSERT_GE(t, 0);
    ASSERT_LT(t, static_cast<int>(mesh.tets.size()));
    const auto& tet = mesh.tets[t];
    EXPECT_TRUE(tet_changes_sign(tet, f));
    for (const int v : s.mesh.faces[i])
      for (const int end : s.vertex_edge[v])
        EXPECT_NE(std::find(tet.begin(), tet.end(), end), tet.end()) << "face " << i;
  }
}

TEST(MarchingTetrahedra, QuadranglesAreSplitAlongTheShortestDiagonal) {
  const TetMesh& mesh = sphere_domain();
  const IsoSurface s = marching_tetrahedra(mesh, sample(mesh.vertices, unit_sphere));
  std::map<int, std::vector<int>> faces_of_tet;
  for (std::size_t i = 0; i < s.facet_tet.size(); ++i)
    faces_of_tet[s.facet_tet[i]].push_back(static_cast<int>(i));
  int quadrangles = 0;
  for (const auto& [tet, faces] : faces_of_tet) {
    if (faces.size() != 2) continue;
    ++quadrangles;
    std::map<int, int> uses;
    for (const int face : faces)
      for (const int v : s.mesh.faces[face]) ++uses[v];
    ASSERT_EQ(uses.size(), 4u);
    std::vector<int> shared, apart;
    for (const auto& [v, n] : uses) (n == 2 ? shared : apart).push_back(v);
    ASSERT_EQ(shared.size(), 2u);
    const auto& p = s.mesh.vertices;
    EXPECT_LE((p[shared[0]] - p[shared[1]]).norm(), (p[apart[0]] - p[apart[1]]).norm());
  }
  EXPECT_GT(quadrangles, 100);
}

TEST(MarchingTetrahedra, SingleTetShortestDiagonalAndOrientation) {
  // Negatives n0, n1 at z = -1, positives at z = 1, f = z: the quadrangle at
  // z = 0 is a parallelogram with corners at the edge midpoints.
  for (const double shift : {2.0, -2.0}) {
    TetMesh mesh;
    mesh.vertices = {Vec3(-1, 0, -1), Vec3(3, 0, -1), Vec3(1, -1, 1), Vec3(1 + shift, 1, 1)};
    mesh.tets = {{0, 1, 2, 3}};
    const auto& v = mesh.vertices;
    if ((v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) < 0)
      std::swap(mesh.tets[0][2], mesh.tets[0][3]);
    const std::vector<double> f = {-1, -1, 1, 1};
    const IsoSurface s = marching_tetrahedra(mesh, f);
    ASSERT_EQ(s.mesh.faces.size(), 2u);
    ASSERT_EQ(s.mesh.vertices.size(), 4u);
    // Corners: midpoints of 0-2, 0-3, 1-3, 1-2; diagonals 0-2/1-3 and 0-3/1-2.
    const Vec3 m02 = (v[0] + v[2]) / 2, m13 = (v[1] + v[3]) / 2, m03 = (v[0] + v[3]) / 2,
               m12 = (v[1] + v[2]) / 2;
    const bool first_shorter = (m02 - m13).norm() < (m03 - m12).norm();
    std::map<int, int> uses;
    for (const auto& face : s.mesh.faces)
      for (const int i : face) ++uses[i];
    std::vector<Vec3> shared;
    for (const auto& [i, n] : uses)
      if (n == 2) shared.push_back(s.mesh.vertices[i]);
    ASSERT_EQ(shared.size(), 2u);
    const Vec3 expected_a = first_shorter ? m02 : m03, expected_b = first_shorter ? m13 : m12;
    EXPECT_TRUE(
        ((shared[0] - expected_a).norm() < 1e-12 && (shared[1] - expected_b).norm() < 1e-12) ||
        ((shared[0] - expected_b).norm() < 1e-12 && (shared[1] - expected_a).norm() < 1e-12))
        << "shift " << shift;
    for (int i = 0; i < 2; ++i) EXPECT_GT(face_normal(s.mesh, i).z(), 0.0);
  }
}

TEST(MarchingTetrahedra, EverySignPatternAndCornerOrderFacesTheGradient) {
  const std::array<Vec3, 4> corners = {Vec3(0.1, -0.2, 0.05), Vec3(1.1, 0.1, -0.1),
                                       Vec3(0.3, 0.9, 0.2), Vec3(0.4, 0.3, 1.2)};
  std::array<int, 4> order = {0, 1, 2, 3};
  do {
    TetMesh mesh;
    for (const int i : order) mesh.vertices.push_back(corners[i]);
    const auto& v = mesh.vertices;
    if ((v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) <= 0) continue;  // keep positive tets
    mesh.tets = {{0, 1, 2, 3}};
    for (int signs = 1; signs < 15; ++signs) {
      std::vector<double> f(4);
      for (int i = 0; i < 4; ++i) f[i] = (signs >> i & 1) ? -0.3 - 0.1 * i : 0.2 + 0.15 * i;
      const IsoSurface s = marching_tetrahedra(mesh, f);
      const int negatives = __builtin_popcount(signs);
      ASSERT_EQ(s.mesh.faces.size(), negatives == 2 ? 2u : 1u);
      ASSERT_EQ(s.mesh.vertices.size(), negatives == 2 ? 4u : 3u);
      const Vec3 g = tet_gradient(mesh, f, 0);
      for (std::size_t i = 0; i < s.mesh.faces.size(); ++i)
        EXPECT_GT(face_normal(s.mesh, static_cast<int>(i)).dot(g), 0.0)
            << "signs " << signs << " order " << order[0] << order[1] << order[2] << order[3];
    }
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(MarchingTetrahedra, TorusHasEulerCharacteristicZero) {
  const double R = 1.0, r = 0.4;
  const TetMesh mesh =
      Domain(grid_points(Vec3(-1.6, -1.6, -0.6), Vec3(1.6, 1.6, 0.6), 0.08, 0.25, 3)).mesh();
  const auto f = sample(mesh.vertices, [&](const Vec3& p) {
    return std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r;
  });
  const IsoSurface s = marching_tetrahedra(mesh, f);
  const SurfaceTopology topology = surface_topology(s.mesh);
  EXPECT_TRUE(topology.closed);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.components, 1u);
  EXPECT_EQ(topology.euler_characteristic, 0);
  EXPECT_EQ(topology.genus, 1);
  EXPECT_GT(enclosed_volume(s.mesh), 0.0);
}

TEST(MarchingTetrahedra, PlaneThroughVerticesIsAnEdgeManifoldDisk) {
  // A regular grid with a layer of vertices exactly on z = 0, where f = 0
  // counts as positive: edges from z < 0 to z = 0 have their isovertex at the
  // z = 0 end, so isovertices coincide there, yet the connectivity is that of
  // a disk.
  const TetMesh mesh =
      Domain(grid_points(Vec3(-1, -1, -0.75), Vec3(1, 1, 0.75), 0.25, 0.0, 0)).mesh();
  for (const double sign : {1.0, -1.0}) {
    const auto f = sample(mesh.vertices, [&](const Vec3& p) { return sign * p.z(); });
    const IsoSurface s = marching_tetrahedra(mesh, f);
    const SurfaceTopology topology = surface_topology(s.mesh);
    EXPECT_TRUE(topology.edge_manifold);
    EXPECT_TRUE(topology.manifold);
    EXPECT_FALSE(topology.closed);
    EXPECT_GT(topology.boundary_edges, 0u);
    EXPECT_EQ(topology.components, 1u);
    EXPECT_EQ(topology.euler_characteristic, 1);
    for (const Vec3& p : s.mesh.vertices) EXPECT_LE(std::abs(p.z()), 1e-12);
    // Facing +z for f = z and -z for f = -z (degenerate faces have no normal).
    double area_up = 0;
    for (std::size_t i = 0; i < s.mesh.faces.size(); ++i) {
      const double nz = face_normal(s.mesh, static_cast<int>(i)).z();
      EXPECT_GE(sign * nz, 0.0);
      area_up += sign * nz / 2;
    }
    EXPECT_NEAR(area_up, 4.0, 1e-9);  // the plane's section of the [-1, 1]^2 box
  }
}

TEST(MarchingTetrahedra, CubeWithVerticesOnItsSurfaceIsClosed) {
  // f = |x|_inf - 1 vanishes at every grid vertex on the cube's surface.
  const TetMesh mesh =
      Domain(grid_points(Vec3::Constant(-1.5), Vec3::Constant(1.5), 0.25, 0.0, 0)).mesh();
  const auto f =
      sample(mesh.vertices, [](const Vec3& p) { return p.lpNorm<Eigen::Infinity>() - 1; });
  ASSERT_GT(std::count(f.begin(), f.end(), 0.0), 100);
  const IsoSurface s = marching_tetrahedra(mesh, f);
  const SurfaceTopology topology = surface_topology(s.mesh);
  EXPECT_TRUE(topology.closed);
  EXPECT_TRUE(topology.manifold);
  EXPECT_EQ(topology.components, 1u);
  EXPECT_EQ(topology.euler_characteristic, 2);
  for (const Vec3& p : s.mesh.vertices) EXPECT_LE(p.lpNorm<Eigen::Infinity>(), 1 + 1e-12);
  // The negative region lies in the cube and holds every grid cell that does
  // not touch one of its 12 edges (each of those cells' tets has a vertex
  // inside the cube).
  const double volume = enclosed_volume(s.mesh);
  EXPECT_LE(volume, 8.0 + 1e-9);
  EXPECT_GE(volume, 8.0 - 12 * 8 * std::pow(0.25, 3));
}

TEST(MarchingTetrahedra, IsovalueShiftsTheLevelSet) {
  const TetMesh& mesh = sphere_domain();
  const IsoSurface at_zero = marching_tetrahedra(mesh, sample(mesh.vertices, unit_sphere));
  const IsoSurface at_one =
      marching_tetrahedra(mesh, sample(mesh.vertices, [](const Vec3& p) { return p.norm(); }), 1.0);
  EXPECT_EQ(at_zero.mesh.faces, at_one.mesh.faces);
  EXPECT_EQ(at_zero.vertex_edge, at_one.vertex_edge);
  for (std::size_t i = 0; i < at_zero.mesh.vertices.size(); ++i)
    EXPECT_LT((at_zero.mesh.vertices[i] - at_one.mesh.vertices[i]).norm(), 1e-12);
}

TEST(MarchingTetrahedra, OutputIsDeterministicInOrderOfFirstAppearance) {
  const TetMesh& mesh = sphere_domain();
  const auto f = sample(mesh.vertices, unit_sphere);
  const IsoSurface a = marching_tetrahedra(mesh, f);
  const IsoSurface b = marching_tetrahedra(mesh, f);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.facet_tet, b.facet_tet);
  EXPECT_EQ(a.vertex_edge, b.vertex_edge);
  EXPECT_TRUE(std::is_sorted(a.facet_tet.begin(), a.facet_tet.end()));
  // The isovertices new to each tet, in tet order, are the next indices.
  int next = 0;
  for (std::size_t begin = 0; begin < a.mesh.faces.size();) {
    std::size_t end = begin;
    std::set<int> fresh;
    for (; end < a.mesh.faces.size() && a.facet_tet[end] == a.facet_tet[begin]; ++end)
      for (const int v : a.mesh.faces[end])
        if (v >= next) fresh.insert(v);
    for (const int v : fresh) ASSERT_EQ(v, next++);
    begin = end;
  }
  EXPECT_EQ(next, static_cast<int>(a.mesh.vertices.size()));
}

TEST(MarchingTetrahedra, RejectsMismatchedOrNonFiniteValues) {
  const TetMesh& mesh = sphere_domain();
  EXPECT_THROW(marching_tetrahedra(mesh, std::vector<double>(3, 0.0)), std::invalid_argument);
  auto f = sample(mesh.vertices, unit_sphere);
  f[5] = std::nan("");
  EXPECT_THROW(marching_tetrahedra(mesh, f), std::invalid_argument);
  const IsoSurface none = marching_tetrahedra(mesh, std::vector<double>(mesh.vertices.size(), 1.0));
  EXPECT_TRUE(none.mesh.faces.empty());
  EXPECT_TRUE(none.mesh.vertices.empty());
}

// ------------------------------------------------------------- Figure 2

using test::Figure2Layout;

TEST(Figure2, UnbiasedLayersAreCrossedAtEdgeMidpoints) {
  for (const auto& [layout, t_expected] : {std::pair{Figure2Layout::kUnbiasedEven, 0.5},
                                           std::pair{Figure2Layout::kBiasedEven, 0.25}}) {
    const Domain d = test::figure2_domain(layout, 300);
    const IsoSurface s = marching_tetrahedra(d.mesh(), d.f());
    for (std::size_t i = 0; i < s.mesh.vertices.size(); ++i) {
      const auto [a, b] = s.vertex_edge[i];
      const bool a_inner = d.vertices()[a].norm() < 1;
      const Vec3 inner = d.vertices()[a_inner ? a : b], outer = d.vertices()[a_inner ? b : a];
      EXPECT_LT((s.mesh.vertices[i] - (inner + t_expected * (outer - inner))).norm(), 1e-12);
    }
  }
}

TEST(Figure2, UnbiasedEvenLayersGiveTheBestTriangles) {
  // The paper's claim: (d) has a higher mean min angle and fewer triangles
  // under 30 degrees than each of (a), (b), (c); random layouts on 3 seeds.
  const int n = 500;
  for (const unsigned seed : {1u, 2u, 3u}) {
    std::map<Figure2Layout, TriangleQuality> q;
    for (const Figure2Layout layout : {Figure2Layout::kBiasedRandom, Figure2Layout::kUnbiasedRandom,
                                       Figure2Layout::kBiasedEven, Figure2Layout::kUnbiasedEven}) {
      const Domain d = test::figure2_domain(layout, n, seed);
      const IsoSurface s = marching_tetrahedra(d.mesh(), d.f());
      const SurfaceTopology topology = surface_topology(s.mesh);
      EXPECT_TRUE(topology.closed && topology.manifold) << test::figure2_label(layout);
      EXPECT_EQ(topology.euler_characteristic, 2) << test::figure2_label(layout);
      q[layout] = triangle_quality(s.mesh);
    }
    const TriangleQuality& best = q[Figure2Layout::kUnbiasedEven];
    for (const Figure2Layout other : {Figure2Layout::kBiasedRandom, Figure2Layout::kUnbiasedRandom,
                                      Figure2Layout::kBiasedEven}) {
      EXPECT_GT(best.mean_min_angle, q[other].mean_min_angle + 5) << test::figure2_label(other);
      EXPECT_LT(best.fraction_below_30, q[other].fraction_below_30) << test::figure2_label(other);
      EXPECT_LT(best.fraction_below_30 * best.count, q[other].fraction_below_30 * q[other].count)
          << test::figure2_label(other);
    }
  }
}


// A closed octahedron-subdivided sphere: 8 * 4^levels faces.
TriangleMesh subdivided_sphere(int levels, double radius, const Vec3& center) {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = middle.try_emplace(key, static_cast<int>(m.vertices.size()));
      if (added) m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> faces;
    for (const auto& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      faces.insert(faces.end(), {{f[0], ab, ca}, {ab, f[1], bc}, {ca, bc, f[2]}, {ab, bc, ca}});
    }
    m.faces = std::move(faces);
  }
  for (Vec3& v : m.vertices) v = center + radius * v;
  return m;
}

void append(TriangleMesh& to, const TriangleMesh& from) {
  const int offset = static_cast<int>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (const auto& f : from.faces) to.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

double mean_edge_length(const TriangleMesh& m) {
  double sum = 0;
  for (const auto& f : m.faces)
    for (int i = 0; i < 3; ++i) sum += (m.vertices[f[i]] - m.vertices[f[(i + 1) % 3]]).norm();
  return sum / (3.0 * static_cast<double>(m.faces.size()));
}

TEST(SmallComponents, ABlobUnderTheMeshResolutionGoesAndTheRestStaysInOrder) {
  const TriangleMesh sphere = subdivided_sphere(4, 1.0, Vec3::Zero());  // 2048 faces
  const double edge = mean_edge_length(sphere);
  TriangleMesh mesh = sphere;
  append(mesh, subdivided_sphere(0, edge, Vec3(3, 0, 0)));  // an octahedron 2 edges wide
  ASSERT_EQ(surface_topology(mesh).components, 2u);
  const RemovedComponents r = remove_small_components(mesh, 4);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.faces, 8);
  ASSERT_EQ(mesh.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(mesh.faces, sphere.faces);
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v)
    EXPECT_EQ(mesh.vertices[v], sphere.vertices[v]);
}

TEST(SmallComponents, ResolvedComponentsStayWhateverTheirSize) {
  TriangleMesh mesh = subdivided_sphere(4, 1.0, Vec3::Zero());
  const double edge = mean_edge_length(mesh);
  // 512 faces, 6 edges of the big sphere wide.
  append(mesh, subdivided_sphere(3, 3 * edge, Vec3(0, 0, 3)));
  append(mesh, subdivided_sphere(4, 1.0, Vec3(5, 0, 0)));
  const std::size_t faces = mesh.faces.size();
  EXPECT_EQ(remove_small_components(mesh, 4).components, 0);
  EXPECT_EQ(mesh.faces.size(), faces);
  EXPECT_EQ(surface_topology(mesh).components, 3u);
}

TEST(SmallComponents, ZeroKeepsEverythingAndTheLargestAlwaysStays) {
  TriangleMesh mesh = subdivided_sphere(1, 0.1, Vec3::Zero());  // 32 faces
  append(mesh, subdivided_sphere(0, 0.1, Vec3(1, 0, 0)));       // 8 faces
  TriangleMesh kept = mesh;
  EXPECT_EQ(remove_small_components(kept, 0).components, 0);
  EXPECT_EQ(kept.faces.size(), 40u);
  // Both are under 1000 edges across: only the one with the most faces stays.
  const RemovedComponents r = remove_small_components(mesh, 1000);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.faces, 8);
  EXPECT_EQ(mesh.faces.size(), 32u);
  EXPECT_EQ(surface_topology(mesh).components, 1u);
  EXPECT_THROW(remove_small_components(mesh, -1), std::invalid_argument);
  EXPECT_THROW(remove_small_components(mesh, std::nan("")), std::invalid_argument);
}

// The faces of `m` on the side z > 0 of their centroid: an open cap.
TriangleMesh upper_half(const TriangleMesh& m) {
  TriangleMesh half = m;
  half.faces.clear();
  const double z = [&] {
    double sum = 0;
    for (const Vec3& v : m.vertices) sum += v.z();
    return sum / static_cast<double>(m.vertices.size());
  }();
  for (const auto& f : m.faces)
    if ((m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]).z() / 3 > z) half.faces.push_back(f);
  return half;
}

TEST(OpenComponents, AnOpenPieceGoesAndClosedOnesStayInOrder) {
  const TriangleMesh sphere = subdivided_sphere(3, 1.0, Vec3::Zero());  // 512 faces
  TriangleMesh mesh = sphere;
  // A closed octahedron stays, however small; an open cap of 256 faces goes.
  append(mesh, subdivided_sphere(0, 0.1, Vec3(0, 0, 2)));
  TriangleMesh cap = upper_half(subdivided_sphere(3, 0.9, Vec3(3, 0, 0)));
  ASSERT_GT(surface_topology(cap).boundary_edges, 0u);
  append(mesh, cap);
  const std::size_t closed_faces = sphere.faces.size() + 8;
  const RemovedComponents r = remove_open_components(mesh);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(static_cast<std::size_t>(r.faces), cap.faces.size());
  ASSERT_EQ(mesh.faces.size(), closed_faces);
  for (std::size_t f = 0; f < sphere.faces.size(); ++f) EXPECT_EQ(mesh.faces[f], sphere.faces[f]);
  const SurfaceTopology topo = surface_topology(mesh);
  EXPECT_TRUE(topo.closed);
  EXPECT_EQ(topo.components, 2u);
}

TEST(OpenComponents, TheLargestStaysEvenWhenOpen) {
  // A one-view scan's surface can run into the domain's boundary: kept.
  TriangleMesh mesh = upper_half(subdivided_sphere(3, 1.0, Vec3::Zero()));
  append(mesh, upper_half(subdivided_sphere(1, 0.2, Vec3(3, 0, 0))));
  const std::size_t largest = upper_half(subdivided_sphere(3, 1.0, Vec3::Zero())).faces.size();
  EXPECT_EQ(remove_open_components(mesh).components, 1);
  EXPECT_EQ(mesh.faces.size(), largest);
  EXPECT_GT(surface_topology(mesh).boundary_edges, 0u);
  EXPECT_EQ(count_boundary_edges(mesh), surface_topology(mesh).boundary_edges);
  EXPECT_EQ(count_boundary_edges(subdivided_sphere(3, 1.0, Vec3::Zero())), 0u);
  TriangleMesh empty;
  EXPECT_EQ(remove_open_components(empty).components, 0);
  EXPECT_EQ(count_boundary_edges(empty), 0u);
}

}  // namespace
}  // namespace pdd
