// The trim's rim remeshed (trim.cpp): the cut through the triangles leaves
// short edges and flat triangles where it passes near a vertex. Within two
// rings of the boundary, rim triangles flattened onto their boundary edge are
// removed, short edges collapsed, edges flipped and vertices
// moved in their tangent planes, each step kept only where it raises the
// smallest angle of the triangles it touches and turns no triangle over.
// Written here because the mesh is a plain face list: CGAL's remeshing
// (Polygon_mesh_processing::isotropic_remeshing) would convert the whole mesh
// to a Surface_mesh and back, and targets edge lengths, not the rim's angles.
#include "contour/rim.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "contour/angles.h"
#include "contour/components.h"

namespace pdd::detail {

namespace {

void remove(std::vector<int>& list, int value) {
  list.erase(std::remove(list.begin(), list.end(), value), list.end());
}

Vec3 normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

// A face list with each vertex's incident faces; removed faces become {-1,-1,-1}.
class Surface {
 public:
  explicit Surface(TriangleMesh& mesh) : x(mesh.vertices), f(mesh.faces), incident(x.size()) {
    for (std::size_t i = 0; i < f.size(); ++i)
      for (int v : f[i]) incident[v].push_back(static_cast<int>(i));
  }

  std::vector<int> faces_of_edge(int a, int b) const {
    std::vector<int> out;
    for (int i : incident[a])
      if (contains(i, b)) out.push_back(i);
    return out;
  }
  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int i : incident[v])
      for (int w : f[i])
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  bool contains(int face, int v) const {
    return f[face][0] == v || f[face][1] == v || f[face][2] == v;
  }
  double worst(const std::vector<int>& faces) const {
    double w = 180;
    for (int i : faces) w = std::min(w, min_angle_degrees(x[f[i][0]], x[f[i][1]], x[f[i][2]]));
    return w;
  }

  // Collapses u into k, which moves to `to`, where the result is manifold,
  // turns no face over and raises the smallest angle around them.
  bool collapse(int u, int k, const Vec3& to) {
    const std::vector<int> shared = faces_of_edge(u, k);
    std::vector<int> common;
    const std::vector<int> nu = neighbours(u), nk = neighbours(k);
    std::set_intersection(nu.begin(), nu.end(), nk.begin(), nk.end(), std::back_inserter(common));
    if (common.size() != shared.size() || shared.empty()) return false;  // the link condition
    std::vector<int> around = incident[u];
    around.insert(around.end(), incident[k].begin(), incident[k].end());
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    const double before = worst(around);
    double after = 180;
    for (int i : around) {
      if (contains(i, u) && contains(i, k)) continue;
      std::array<Vec3, 3> p;
      for (int j = 0; j < 3; ++j) p[j] = f[i][j] == u || f[i][j] == k ? to : x[f[i][j]];
      const Vec3 was = normal(x[f[i][0]], x[f[i][1]], x[f[i][2]]);
      const Vec3 now = normal(p[0], p[1], p[2]);
      if (now.dot(was) <= 0.5 * now.norm() * was.norm()) return false;
      after = std::min(after, min_angle_degrees(p[0], p[1], p[2]));
    }
    if (after <= before) return false;
    for (int i : shared) {
      for (int v : f[i])
        if (v != u && v != k) remove(incident[v], i);
      f[i] = {-1, -1, -1};
    }
    for (int i : incident[u]) {
      if (f[i][0] < 0) continue;
      for (int& v : f[i])
        if (v == u) v = k;
      incident[k].push_back(i);
    }
    incident[u].clear();
    incident[k].erase(
        std::remove_if(incident[k].begin(), incident[k].end(), [&](int i) { return f[i][0] < 0; }),
        incident[k].end());
    std::sort(incident[k].begin(), incident[k].end());
    incident[k].erase(std::unique(incident[k].begin(), incident[k].end()), incident[k].end());
    x[k] = to;
    return true;
  }

  void remove_face(int face) {
    for (int v : f[face]) remove(incident[v], face);
    f[face] = {-1, -1, -1};
  }

  // Flips the interior edge (a, b) where its two faces are nearly coplanar and
  // the flip raises their smallest angle.
  bool flip(int a, int b) {
    const std::vector<int> two = faces_of_edge(a, b);
    if (two.size() != 2) return false;
    auto apex = [&](int i) {
      for (int v : f[two[i]])
        if (v != a && v != b) return v;
      return -1;
    };
    const int c = apex(0), d = apex(1);
    if (!faces_of_edge(c, d).empty()) return false;
    // The orientation of face 0 as (a, b, c) or (b, a, c).
    const std::array<int, 3>& f0 = f[two[0]];
    int i0 = 0;
    while (f0[i0] != a) ++i0;
    const bool ab = f0[(i0 + 1) % 3] == b;
    const int p = ab ? a : b, q = ab ? b : a;  // face 0 is (p, q, c), face 1 is (q, p, d)
    const Vec3 n0 = normal(x[p], x[q], x[c]), n1 = normal(x[q], x[p], x[d]);
    if (n0.dot(n1) < std::cos(M_PI / 9) * n0.norm() * n1.norm()) return false;  // 20 degrees
    const std::array<int, 3> g0 = {p, d, c}, g1 = {q, c, d};
    const Vec3 m0 = normal(x[g0[0]], x[g0[1]], x[g0[2]]), m1 = normal(x[g1[0]], x[g1[1]], x[g1[2]]);
    const Vec3 n = n0 + n1;
    if (m0.dot(n) <= 0 || m1.dot(n) <= 0) return false;
    const double before = worst(two);
    const double after =
        std::min(min_angle_degrees(x[p], x[d], x[c]), min_angle_degrees(x[q], x[c], x[d]));
    if (after <= before) return false;
    f[two[0]] = g0;
    f[two[1]] = g1;
    remove(incident[p], two[1]);
    remove(incident[q], two[0]);
    incident[c].push_back(two[1]);
    incident[d].push_back(two[0]);
    return true;
  }

  // Moves v to `to` where that turns no face over and raises its smallest angle.
  bool move(int v, const Vec3& to) {
    const double before = worst(incident[v]);
    double after = 180;
    for (int i : incident[v]) {
      std::array<Vec3, 3> p;
      for (int j = 0; j < 3; ++j) p[j] = f[i][j] == v ? to : x[f[i][j]];
      const Vec3 was = normal(x[f[i][0]], x[f[i][1]], x[f[i][2]]);
      const Vec3 now = normal(p[0], p[1], p[2]);
      if (now.dot(was) <= 0.5 * now.norm() * was.norm()) return false;
      after = std::min(after, min_angle_degrees(p[0], p[1], p[2]));
    }
    if (after <= before) return false;
    x[v] = to;
    return true;
  }

  std::vector<Vec3>& x;
  std::vector<std::array<int, 3>>& f;
  std::vector<std::vector<int>> incident;
};

}  // namespace

void remesh_rim(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& boundary, double edge) {
  Surface s(mesh);
  const std::size_t n = s.x.size();
  // The band: boundary vertices and two rings around them.
  std::vector<int> band;
  std::vector<char> rim(n, 0), in_band(n, 0);
  for (const auto& [a, b] : boundary)
    for (int v : {a, b})
      if (!rim[v]) {
        rim[v] = in_band[v] = 1;
        band.push_back(v);
      }
  for (int ring = 0; ring < 2; ++ring) {
    const std::size_t size = band.size();
    for (std::size_t i = 0; i < size; ++i)
      for (int w : s.neighbours(band[i]))
        if (!in_band[w]) {
          in_band[w] = 1;
          band.push_back(w);
        }
  }
  std::sort(band.begin(), band.end());

  for (int round = 0; round < 3; ++round) {
    // A rim triangle flattened onto its boundary edge (an angle over 120 degrees
    // at its inner corner) goes: the rim then runs through that corner.
    for (int v : band) {
      if (!rim[v]) continue;
      for (int face : std::vector<int>(s.incident[v])) {
        const std::array<int, 3> t = s.f[face];
        if (t[0] < 0) continue;
        for (int i = 0; i < 3; ++i) {
          const int a = t[i], b = t[(i + 1) % 3], c = t[(i + 2) % 3];
          if (rim[c] || s.faces_of_edge(a, b).size() != 1) continue;
          const Vec3 u = s.x[a] - s.x[c], w = s.x[b] - s.x[c];
          if (std::atan2(u.cross(w).norm(), u.dot(w)) > 2 * M_PI / 3) {  // 120 degrees
            s.remove_face(face);
            rim[c] = 1;
            break;
          }
        }
      }
    }
    // Short edges at the rim: an inner vertex goes onto the rim vertex (the
    // rim stays on the cut), two rim vertices meet halfway.
    for (int v : band) {
      if (!rim[v] || s.incident[v].empty()) continue;
      for (int w : s.neighbours(v)) {
        if ((s.x[v] - s.x[w]).norm() >= 0.4 * edge) continue;
        const bool boundary_edge = s.faces_of_edge(v, w).size() == 1;
        if (rim[w] && !boundary_edge) continue;  // would pinch the rim
        const Vec3 to = rim[w] ? 0.5 * (s.x[v] + s.x[w]) : s.x[v];
        if (s.collapse(w, v, to)) break;
      }
    }
    for (int v : band) {
      if (s.incident[v].empty()) continue;
      for (int w : s.neighbours(v))
        if (v < w && in_band[w]) s.flip(v, w);
    }
    // Inner band vertices toward the centroid of their neighbours, rim
    // vertices toward their rim neighbours' midpoint.
    for (int v : band) {
      if (s.incident[v].empty()) continue;
      const std::vector<int> around = s.neighbours(v);
      Vec3 to = Vec3::Zero();
      if (rim[v]) {
        int ends = 0;
        for (int w : around)
          if (s.faces_of_edge(v, w).size() == 1) {
            to += 0.5 * s.x[w];
            ++ends;
          }
        if (ends != 2) continue;
      } else {
        for (int w : around) to += s.x[w];
        to /= static_cast<double>(around.size());
      }
      // Within the vertex's tangent plane, so that it stays on the surface to second order.
      Vec3 nv = Vec3::Zero();
      for (int i : s.incident[v]) nv += normal(s.x[s.f[i][0]], s.x[s.f[i][1]], s.x[s.f[i][2]]);
      if (nv.norm() == 0) continue;
      nv.normalize();
      to -= (to - s.x[v]).dot(nv) * nv;
      s.move(v, s.x[v] + 0.5 * (to - s.x[v]));
    }
  }
  mesh.faces.erase(std::remove_if(mesh.faces.begin(), mesh.faces.end(),
                                  [](const std::array<int, 3>& f) { return f[0] < 0; }),
                   mesh.faces.end());
  drop_unused_vertices(mesh);
}

}  // namespace pdd::detail
