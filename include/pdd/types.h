// Plain data types shared by every stage. Public headers speak in these types,
// never in CGAL's, so that a client of the library never compiles CGAL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace pdd {

using Vec3 = Eigen::Vector3d;

// An input point set X = {(p_i, n_i)} (§3.1). Normals are optional; when
// present there is exactly one per point.
struct PointSet {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  // empty, or normals.size() == points.size()

  bool has_normals() const { return !normals.empty(); }
  std::size_t size() const { return points.size(); }
};

// An indexed triangle mesh; faces index into vertices, counter-clockwise
// seen from outside.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
};

// A tetrahedral mesh; every tet is positively oriented:
// (v1 - v0) . ((v2 - v0) x (v3 - v0)) > 0.
struct TetMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 4>> tets;
};

}  // namespace pdd
