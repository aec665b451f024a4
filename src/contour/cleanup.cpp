// Clean-up of the final isosurface: Lawson edge flips, collapses of the short
// edge of needles, and vertices relaxed toward their neighbours' centroid,
// where the surface is nearly flat or the change barely moves it. Marching
// tetrahedra ties the connectivity to the tets' edges, so even with crossings
// at the midpoints (§3.3) an irregular crossing tet leaves a cap or a needle
// that no move of the domain's vertices fixes (docs/benchmarks.md,
// "Isosurface clean-up"). CGAL's Surface_mesh and Euler operations keep the
// halfedge bookkeeping.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/squared_distance_3.h>
#include <Eigen/Cholesky>
#include <pdd/contour.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/cancellation.h"
#include "contour/angles.h"

namespace pdd {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
using Halfedge = Mesh::Halfedge_index;
using Edge = Mesh::Edge_index;
using Face = Mesh::Face_index;

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * kPi / 180.0; }

// The angle at `apex` of the triangle (apex, u, w).
double angle(const Vec3& apex, const Vec3& u, const Vec3& w) {
  const Vec3 x = u - apex, y = w - apex;
  return std::atan2(x.cross(y).norm(), x.dot(y));
}

// Whether the angles at c and at d opposite the edge (a, b) sum to more than
// pi (by 1e-12): sin(alpha + beta) < 0, from the sines and cosines scaled by
// the edges' lengths, without two atan2 per edge visited by the flips.
bool opposite_angles_exceed_pi(const Vec3& c, const Vec3& d, const Vec3& a, const Vec3& b) {
  const Vec3 x1 = a - c, y1 = b - c, x2 = b - d, y2 = a - d;
  const double s1 = x1.cross(y1).norm(), c1 = x1.dot(y1);
  const double s2 = x2.cross(y2).norm(), c2 = x2.dot(y2);
  const double scale =
      std::sqrt(x1.squaredNorm() * y1.squaredNorm() * x2.squaredNorm() * y2.squaredNorm());
  return s1 * c2 + c1 * s2 < -1e-12 * scale;
}

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0 ? Vec3(n / length) : Vec3::Zero();
}

class Cleaner {
 public:
  Cleaner(Mesh& mesh, const CleanupOptions& options)
      : m_(mesh), options_(options), min_cosine_(std::cos(radians(options.max_dihedral_degrees))) {}

  // Lawson's flips: an edge whose two opposite angles sum to more than pi is
  // swapped (on a plane this maximizes the smallest angle, and terminates;
  // the cap guards the nearly flat case).
  int flip_all() {
    std::vector<Edge> stack(m_.edges().begin(), m_.edges().end());
    std::vector<char> queued(m_.number_of_edges() + m_.number_of_removed_edges(), 0);
    for (Edge e : stack) queued[e.idx()] = 1;
    const std::size_t cap = 10 * m_.number_of_edges();
    int flips = 0;
    for (std::size_t visits = 0; !stack.empty() && static_cast<std::size_t>(flips) < cap;
         ++visits) {
      const Edge e = stack.back();
      stack.pop_back();
      queued[e.idx()] = 0;
      detail::poll_every(visits);  // the run's cancellation
      if (m_.is_removed(e) || !should_flip(e)) continue;
      const Halfedge h = m_.halfedge(e);
      CGAL::Euler::flip_edge(h, m_);
      ++flips;
      for (Halfedge side :
           {m_.next(h), m_.prev(h), m_.next(m_.opposite(h)), m_.prev(m_.opposite(h))}) {
        const Edge s = m_.edge(side);
        if (!queued[s.idx()]) {
          queued[s.idx()] = 1;
          stack.push_back(s);
        }
      }
    }
    return flips;
  }

  // Needles (shortest_edge_if_needle) lose their shortest edge, collapsed to
  // its midpoint, or else to one of its ends, when the link condition holds
  // and no remaining triangle turns by more than max_dihedral_degrees (or,
  // to the midpoint, none folds and the ends move by at most max_deviation of
  // the needle's longest edge). Where the link condition fails because a
  // triangle's far corner has valence three, that corner is removed instead
  // (its three triangles become one).
  int collapse_needles() {
    int collapses = 0;
    for (Face f : std::vector<Face>(m_.faces().begin(), m_.faces().end())) {
      detail::poll_every(f.idx());
      if (m_.is_removed(f)) continue;
      const Halfedge h = shortest_edge_if_needle(f);
      if (h == Mesh::null_halfedge()) continue;
      if (!CGAL::Euler::does_satisfy_link_condition(m_.edge(h), m_)) {
        for (Halfedge side : {h, m_.opposite(h)})
          if (!m_.is_border(side) && remove_valence_three(m_.target(m_.next(side)))) {
            ++collapses;
            break;
          }
        continue;
      }
      const Vec3 a = position(m_.source(h)), b = position(m_.target(h));
      const Vec3 midpoint = 0.5 * (a + b);
      Vec3 target;
      if (collapse_keeps_orientation(h, midpoint))
        target = midpoint;
      else if (collapse_keeps_orientation(h, a))
        target = a;
      else if (collapse_keeps_orientation(h, b))
        target = b;
      else if (0.5 * (a - b).norm() <= options_.max_deviation * longest_edge(m_.face(h)) &&
               collapse_keeps_orientation(h, midpoint, /*min_cosine=*/0))
        target = midpoint;  // the ends move by less than the bound: no feature to keep
      else
        continue;
      const Vertex kept = CGAL::Euler::collapse_edge(m_.edge(h), m_);
      m_.point(kept) = point(target);
      ++collapses;
    }
    return collapses;
  }

  // Each inner vertex where the surface is nearly flat moves halfway to the
  // centroid of its neighbours, kept on its star (the closest point of its
  // triangles, so the surface stays the piecewise-linear one), where that
  // raises the smallest angle around it and turns no triangle by more than
  // max_dihedral_degrees.
  int relax() {
    int moves = 0;
    std::vector<std::pair<Vec3, Vec3>> link;
    for (Vertex v : m_.vertices()) {
      detail::poll_every(v.idx());
      if (m_.is_border(v)) continue;
      const Vec3 x = position(v);
      Vec3 centroid = Vec3::Zero(), n = Vec3::Zero();
      int valence = 0;
      link.clear();  // the far edge of each triangle, in order
      for (Halfedge h : m_.halfedges_around_target(m_.halfedge(v))) {
        const Vec3 a = position(m_.source(h)), b = position(m_.target(m_.next(h)));
        link.emplace_back(a, b);
        centroid += a;
        n += (a - x).cross(b - x);
        ++valence;
      }
      if (valence < 3 || n.norm() == 0) continue;
      n.normalize();
      bool flat = true;
      for (const auto& [a, b] : link) flat = flat && unit_normal(x, a, b).dot(n) >= min_cosine_;
      if (!flat) continue;
      // Halfway to the centroid in the tangent plane, lifted onto the quadric
      // h = c0 u^2 + c1 u v + c2 v^2 fitted to the neighbours' heights over it,
      // so that the vertex stays on the surface to second order.
      const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
      Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
      Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
      for (const auto& [a, b] : link) {
        const Vec3 d = a - x;
        const double u = d.dot(e1), w = d.dot(e2);
        const Eigen::Vector3d row(u * u, u * w, w * w);
        normal_matrix += row * row.transpose();
        rhs += row * d.dot(n);
      }
      const Eigen::LDLT<Eigen::Matrix3d> fit(normal_matrix);
      if (fit.info() != Eigen::Success || fit.vectorD().minCoeff() <= 0) continue;
      const Eigen::Vector3d c = fit.solve(rhs);
      const Vec3 step = 0.5 * (centroid / valence - x);
      const double u = step.dot(e1), w = step.dot(e2);
      const Vec3 target = x + u * e1 + w * e2 + (c[0] * u * u + c[1] * u * w + c[2] * w * w) * n;
      double before = 180, after = 180;
      bool turns = false;
      for (const auto& [a, b] : link) {
        before = std::min(before, detail::min_angle_degrees(x, a, b));
        after = std::min(after, detail::min_angle_degrees(target, a, b));
        turns = turns || unit_normal(target, a, b).dot(unit_normal(x, a, b)) < min_cosine_;
      }
      if (turns || after <= before) continue;
      m_.point(v) = point(target);
      ++moves;
    }
    return moves;
  }

 private:
  static Kernel::Point_3 point(const Vec3& x) { return Kernel::Point_3(x.x(), x.y(), x.z()); }

  Vec3 position(Vertex v) const {
    const auto& p = m_.point(v);
    return Vec3(p.x(), p.y(), p.z());
  }

  // Edge (a, b) between triangles (a, b, c) and (b, a, d).
  bool should_flip(Edge e) const {
    if (m_.is_border(e)) return false;
    const Halfedge h = m_.halfedge(e);
    const Vertex a = m_.source(h), b = m_.target(h);
    const Vertex c = m_.target(m_.next(h));
    const Vertex d = m_.target(m_.next(m_.opposite(h)));
    if (c == d) return false;
    const Vec3 pa = position(a), pb = position(b), pc = position(c), pd = position(d);
    if (!opposite_angles_exceed_pi(pc, pd, pa, pb)) return false;  // Delaunay already
    if (m_.halfedge(c, d).is_valid()) return false;                // would not stay manifold
    const Vec3 n1 = unit_normal(pa, pb, pc), n2 = unit_normal(pb, pa, pd);
    if (n1.dot(n2) < min_cosine_ &&
        flip_deviation(pa, pb, pc, pd) > options_.max_deviation * (pb - pa).norm())
      return false;  // neither nearly flat nor a flip that barely moves the surface
    // The new triangles (c, a, d) and (d, b, c) must face the same way.
    const Vec3 n = n1 + n2;
    return unit_normal(pc, pa, pd).dot(n) > 0 && unit_normal(pd, pb, pc).dot(n) > 0;
  }

  // How far a flip of (a, b) to (c, d) moves the surface: the larger of the
  // distances from the new edge's midpoint to the old triangles and from the
  // old edge's midpoint to the new ones (a cap's flip barely moves it).
  static double flip_deviation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const auto squared = [](const Vec3& x, const Vec3& p, const Vec3& q, const Vec3& r) {
      return CGAL::squared_distance(point(x), Kernel::Triangle_3(point(p), point(q), point(r)));
    };
    const Vec3 new_mid = 0.5 * (c + d), old_mid = 0.5 * (a + b);
    const double to_old = std::min(squared(new_mid, a, b, c), squared(new_mid, b, a, d));
    const double to_new = std::min(squared(old_mid, c, a, d), squared(old_mid, d, b, c));
    return std::sqrt(std::max(to_old, to_new));
  }

  // Removes v if it is an inner vertex of valence three whose one remaining
  // triangle turns from none of its three by more than max_dihedral_degrees,
  // or lies within max_deviation of its longest edge from v (and is not
  // already a face, as in a tetrahedron).
  bool remove_valence_three(Vertex v) {
    if (m_.is_border(v) || m_.degree(v) != 3) return false;
    std::array<Vertex, 3> ring;
    std::array<Halfedge, 3> link;  // the edge of each triangle opposite v
    std::array<Vec3, 3> normals;
    int i = 0;
    for (Halfedge h : m_.halfedges_around_target(m_.halfedge(v))) {
      ring[i] = m_.source(h);
      link[i] = m_.prev(h);
      normals[i] =
          unit_normal(position(m_.source(h)), position(v), position(m_.target(m_.next(h))));
      ++i;
    }
    for (Halfedge l : link) {
      const Halfedge outside = m_.opposite(l);
      if (m_.is_border(outside)) continue;
      const Vertex corner = m_.target(m_.next(outside));
      if (std::find(ring.begin(), ring.end(), corner) != ring.end()) return false;
    }
    const Vec3 p0 = position(ring[0]), p1 = position(ring[1]), p2 = position(ring[2]);
    Vec3 n = unit_normal(p0, p1, p2);
    if (n.dot(normals[0] + normals[1] + normals[2]) < 0) n = -n;
    // A corner over the new triangle by at most max_deviation of its longest
    // edge is removed however its triangles turn (a small spike, no feature).
    const bool low =
        std::abs((position(v) - p0).dot(n)) <= options_.max_deviation * longest_edge(p0, p1, p2);
    if (!low)
      for (const Vec3& m : normals)
        if (n.dot(m) < min_cosine_) return false;
    CGAL::Euler::remove_center_vertex(m_.halfedge(v), m_);
    return true;
  }

  // The shortest edge of f if f is a needle: its smallest angle is under
  // needle_angle_degrees and its shortest edge at most half the next one (a
  // cap, with two short edges around a flat angle, is left to the flips).
  Halfedge shortest_edge_if_needle(Face f) const {
    Halfedge h = m_.halfedge(f);
    std::array<std::pair<double, Halfedge>, 3> edges;
    for (int i = 0; i < 3; ++i, h = m_.next(h))
      edges[i] = {(position(m_.target(h)) - position(m_.source(h))).norm(), h};
    std::sort(edges.begin(), edges.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    const Halfedge shortest = edges[0].second;
    if (!(edges[0].first <= 0.5 * edges[1].first)) return Mesh::null_halfedge();
    const double smallest_angle =
        angle(position(m_.target(m_.next(shortest))), position(m_.source(shortest)),
              position(m_.target(shortest)));
    return smallest_angle < radians(options_.needle_angle_degrees) ? shortest
                                                                   : Mesh::null_halfedge();
  }

  static double longest_edge(const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  }
  double longest_edge(Face f) const {
    const Halfedge h = m_.halfedge(f);
    return longest_edge(position(m_.source(h)), position(m_.target(h)),
                        position(m_.target(m_.next(h))));
  }

  // Every triangle around the two ends of h, but the two that vanish, keeps
  // its normal within max_dihedral_degrees (or `min_cosine`) when both ends
  // move to `target`.
  bool collapse_keeps_orientation(Halfedge h, const Vec3& target) const {
    return collapse_keeps_orientation(h, target, min_cosine_);
  }
  bool collapse_keeps_orientation(Halfedge h, const Vec3& target, double min_cosine) const {
    const Face gone1 = m_.face(h), gone2 = m_.face(m_.opposite(h));
    for (Vertex end : {m_.source(h), m_.target(h)})
      for (Halfedge around : m_.halfedges_around_target(m_.halfedge(end))) {
        const Face f = m_.face(around);
        if (f == Mesh::null_face() || f == gone1 || f == gone2) continue;
        Vec3 before[3], after[3];
        Halfedge k = m_.halfedge(f);
        for (int i = 0; i < 3; ++i, k = m_.next(k)) {
          const Vertex v = m_.target(k);
          before[i] = position(v);
          after[i] = (v == m_.source(h) || v == m_.target(h)) ? target : before[i];
        }
        const Vec3 n0 = unit_normal(before[0], before[1], before[2]);
        const Vec3 n1 = unit_normal(after[0], after[1], after[2]);
        if (n0.dot(n1) < min_cosine) return false;
      }
    return true;
  }

  Mesh& m_;
  const CleanupOptions& options_;
  const double min_cosine_;
};

}  // namespace

CleanupReport cleanup_isosurface(TriangleMesh& mesh, const CleanupOptions& options) {
  if (!(options.max_dihedral_degrees >= 0 && options.max_dihedral_degrees < 90))
    throw std::invalid_argument(
        "cleanup_isosurface: the dihedral bound must be in [0, 90) degrees, got " +
        std::to_string(options.max_dihedral_degrees));
  if (!(options.max_deviation >= 0))
    throw std::invalid_argument("cleanup_isosurface: max_deviation must be >= 0, got " +
                                std::to_string(options.max_deviation));
  if (options.relax_rounds < 0)
    throw std::invalid_argument("cleanup_isosurface: relax_rounds must be >= 0, got " +
                                std::to_string(options.relax_rounds));
  if (!(options.needle_angle_degrees >= 0 && options.needle_angle_degrees < 60))
    throw std::invalid_argument(
        "cleanup_isosurface: the needle angle must be in [0, 60) degrees, got " +
        std::to_string(options.needle_angle_degrees));
  Mesh m;
  std::vector<Vertex> vertex;
  vertex.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices)
    vertex.push_back(m.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (std::size_t k = 0; k < mesh.faces.size(); ++k) {
    const auto& f = mesh.faces[k];
    if (m.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]) == Mesh::null_face())
      throw std::invalid_argument("cleanup_isosurface: the mesh is not an oriented manifold");
    detail::poll_every(k);
  }

  Cleaner cleaner(m, options);
  CleanupReport report;
  report.flips = cleaner.flip_all();
  report.collapses = cleaner.collapse_needles();
  if (report.collapses > 0) report.flips += cleaner.flip_all();
  for (int round = 0; round < options.relax_rounds; ++round) {
    report.moves += cleaner.relax();
    report.collapses += cleaner.collapse_needles();  // the moves leave some
    report.flips += cleaner.flip_all();
  }

  // Read back, renumbering the vertices that remain in their old order.
  std::vector<int> index(m.number_of_vertices() + m.number_of_removed_vertices(), -1);
  mesh.vertices.clear();
  for (Vertex v : m.vertices()) {
    index[v.idx()] = static_cast<int>(mesh.vertices.size());
    const auto& p = m.point(v);
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  mesh.faces.clear();
  for (Face f : m.faces()) {
    std::array<int, 3> face{};
    int i = 0;
    for (Vertex v : m.vertices_around_face(m.halfedge(f))) face[i++] = index[v.idx()];
    mesh.faces.push_back(face);
  }
  return report;
}

}  // namespace pdd
