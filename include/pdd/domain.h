// The discrete domain (§2.2, §3.2): a 3D Delaunay triangulation carrying a
// piecewise-linear function f at its vertices. CGAL stays in the
// implementation; this header speaks in dense indices and Eigen vectors.
#pragma once

#include <pdd/types.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace pdd {

// Initialization of §3.2. Defaults are the paper's.
struct DomainOptions {
  // At most this ratio: a larger sphere only spends the domain's vertices far
  // from the data, and with enough orders of magnitude between the input and
  // the sphere the triangulation's constructions lose their precision.
  static constexpr double kMaxEnlargeRatio = 100;
  double enlarge_ratio = 1.4;      // radius of the domain sphere / radius of the input's bounding sphere
  int sphere_points = 100;         // points spread uniformly on the domain sphere
  // Delaunay refinement: circumradius / shortest edge <= this. At least
  // kMinRadiusEdgeBound: circumcentre insertion meets 1 with a few hundred
  // points, and below 0.9 it ran to max_refinement_points (the regular
  // tet's sqrt(6)/4 = 0.61 is the lowest ratio there is).
  static constexpr double kMinRadiusEdgeBound = 1;
  double radius_edge_bound = 1.3;
  int max_refinement_points = 200000;  // safety budget for the refinement (never reached in practice)
};

// Per-vertex flags.
enum VertexFlag : std::uint8_t {
  kOnBoundarySphere = 1,  // lies on the sphere that bounds the domain
};

// Where a point falls in the domain: the tet and its barycentric coordinates
// (which sum to 1 and are all >= 0 up to rounding). tet == -1 when outside.
struct Location {
  int tet = -1;
  std::array<double, 4> barycentric{{0, 0, 0, 0}};
};

// Statistics of the initial Delaunay refinement.
struct RefinementReport {
  int inserted = 0;           // circumcenters inserted
  int remaining_bad = 0;      // tets still above the bound: boundary cells whose circumcenter
                              // lies outside the domain, or the point budget ran out
  double worst_radius_edge = 0;  // largest ratio among all tets after refinement
};

class Domain {
 public:
  Domain();
  // The Delaunay triangulation of the given points (duplicates are merged;
  // vertex i of the result is the first occurrence). f starts at 0.
  explicit Domain(const std::vector<Vec3>& points, const std::vector<std::uint8_t>& flags = {});
  Domain(Domain&&) noexcept;
  Domain& operator=(Domain&&) noexcept;
  Domain(const Domain&);
  Domain& operator=(const Domain&);
  ~Domain();

  // §3.2: the bounding sphere (c, r) of the input, `sphere_points` points on
  // the sphere of radius enlarge_ratio * r, then Delaunay refinement until
  // every tet's radius-edge ratio is at most radius_edge_bound.
  static Domain initial(const PointSet& input, const DomainOptions& options = {},
                        RefinementReport* report = nullptr);

  // Dense, stable indices: vertex i keeps index i across insertions and moves.
  std::size_t num_vertices() const;
  std::size_t num_tets() const;
  const std::vector<Vec3>& vertices() const;
  // Finite tets, positively oriented. Rebuilt after each modification.
  const std::vector<std::array<int, 4>>& tets() const;
  // For tet t and i in 0..3: the tet opposite vertex i, or -1 on the hull.
  const std::vector<std::array<int, 4>>& tet_neighbors() const;
  // vertices() and tets() together, for the stages that only need geometry.
  const TetMesh& mesh() const;

  // The piecewise-linear function f, one value per vertex.
  const std::vector<double>& f() const;
  void set_f(std::vector<double> values);

  const std::vector<std::uint8_t>& flags() const;
  bool on_boundary_sphere(int vertex) const;
  // The sphere bounding the domain (for Domain::initial) or the bounding
  // sphere of the vertices otherwise.
  Vec3 center() const;
  double radius() const;

  // Point location (§3.5, the sampling matrix Phi; §3.3, carrying f over).
  Location locate(const Vec3& p) const;
  // The same, walking from the tets of `near_vertex`: a few steps when p is
  // close to it (a vertex's new position), instead of a walk across the domain.
  Location locate(const Vec3& p, int near_vertex) const;
  // The same, walking from where a nearby point was located (near.tet >= 0):
  // points located in spatial order, each from the one before.
  Location locate(const Vec3& p, const Location& near) const;
  // Value of the piecewise-linear interpolant of `values` at p; p must lie in
  // the domain (throws std::out_of_range otherwise).
  double interpolate(const Vec3& p, const std::vector<double>& values) const;
  // The same at a point already located (at.tet >= 0).
  double interpolate(const Location& at, const std::vector<double>& values) const;

  // Inserts points; each new vertex gets f interpolated in the tet that
  // contained it before insertion. The new vertices are numbered after the
  // existing ones, in spatial (Hilbert) order. Returns their indices in the
  // order of `points` (points that coincide with an existing vertex are not
  // inserted and are not returned). Points outside the domain are an
  // std::invalid_argument.
  std::vector<int> insert(const std::vector<Vec3>& points, std::uint8_t flags = 0);

  // Delaunay refinement by circumcenter insertion (worst tet first) until
  // every tet has radius-edge ratio <= radius_edge_bound and circumradius <=
  // max_circumradius, or max_points were inserted. Cells whose circumcenter
  // lies outside the domain are left. New vertices get f by interpolation.
  RefinementReport delaunay_refine(double radius_edge_bound, int max_points,
                                   double max_circumradius = std::numeric_limits<double>::infinity());

  // Moves every vertex to new_positions[i], rebuilds the Delaunay
  // triangulation and carries f over by barycentric interpolation in the old
  // one (§3.3, "Linear Solver"). Vertices keep their indices.
  void move_vertices(const std::vector<Vec3>& new_positions);
  // Moves every vertex and center() by `offset`, keeping the tets and f: a
  // translation keeps a Delaunay triangulation Delaunay, up to the rounding of
  // the new coordinates. For a domain built in coordinates relative to some
  // centre and handed back in the caller's (pdd::reconstruct).
  void translate(const Vec3& offset);
  // The same on a new domain, this one unchanged (no copy of it is made).
  Domain moved(const std::vector<Vec3>& new_positions) const;
  // The same with f at the new positions given (one value per vertex) by a
  // caller that has located them already.
  Domain moved(std::vector<Vec3> new_positions, std::vector<double> f) const;

  // Frees the Delaunay triangulation behind point location, insertion and the
  // moves (about 500 bytes per vertex; the vertices, tets, neighbours and f
  // stay, and a copy is released too). The first call that needs it rebuilds
  // it from the tets, the same, in linear time. For a solve that has located
  // its samples and needs only the tets. Not concurrently with other calls on
  // this domain.
  void release_triangulation() const;
  bool triangulation_released() const;

  // Frees the tets and their neighbours too, keeping the vertices, f, flags,
  // centre and radius: for a domain about to be replaced by moved() (the old
  // and the new tets together are the optimizer's peak of memory). Until
  // rebuild_tets(), only moved() and the vertex, value and flag accessors may
  // be called. rebuild_tets() makes the Delaunay tets of the vertices again
  // (the domain's tets, in concurrent_delaunay's order).
  void release_tets();
  void rebuild_tets();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Radius-edge ratio of a tet: circumradius / shortest edge (sqrt(6)/4 for the
// regular tet).
double radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace pdd
