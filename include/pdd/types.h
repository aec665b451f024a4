// Plain data types shared by every stage. Public headers speak in these types,
// never in CGAL's, so that a client of the library never compiles CGAL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace pdd {

using Vec3 = Eigen::Vector3d;

// A scalar property of each point or vertex, as a PLY file names and types
// it: colours ("red", "green", "blue", "alpha"), "intensity", a label.
struct Attribute {
  std::string name;
  // The PLY type it is stored in, and written back in: char uchar short ushort
  // int uint float double. Colours are uchar (0-255) or float/double (0-1).
  std::string type = "float";
  std::vector<double> values;  // one per point or vertex
};

// Whether `name` is one of the colour channels red, green, blue, alpha.
inline bool is_colour(const std::string& name) {
  return name == "red" || name == "green" || name == "blue" || name == "alpha";
}

// An input point set X = {(p_i, n_i)} (§3.1). Normals are optional; when
// present there is exactly one per point. So are attributes, each with one
// value per point.
struct PointSet {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  // empty, or normals.size() == points.size()
  std::vector<Attribute> attributes;

  bool has_normals() const { return !normals.empty(); }
  std::size_t size() const { return points.size(); }

  // Keeps the points i with keep[i] != 0 (with their normals and attributes), in order.
  void keep(const std::vector<char>& keep) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!keep[i]) continue;
      points[out] = points[i];
      if (has_normals()) normals[out] = normals[i];
      for (Attribute& a : attributes) a.values[out] = a.values[i];
      ++out;
    }
    points.resize(out);
    if (has_normals()) normals.resize(out);
    for (Attribute& a : attributes) a.values.resize(out);
  }
};

// An indexed triangle mesh; faces index into vertices, counter-clockwise
// seen from outside. Attributes, when there are any, have one value per vertex.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
  std::vector<Attribute> attributes;
};

// A tetrahedral mesh; every tet is positively oriented:
// (v1 - v0) . ((v2 - v0) x (v3 - v0)) > 0.
struct TetMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 4>> tets;
};

}  // namespace pdd
