// Adaptive refinement, §3.4: the refinement strategy (rules 1-5) and the
// trisection / bisection schemes of Figure 6.
#include <pdd/refine.h>

#include "common/cancellation.h"

#include <algorithm>
#include <set>
#include <tuple>

namespace pdd {

int refinement_rule(const Isofacet& facet, double ratio, double draw) {
  if (ratio <= 1) return 0;
  // Trisection multiplies the facet count by 9 (case 1) or about 12 (case 2).
  const double trisect_above = facet.is_triangle() ? 9.0 : 12.0;
  if (ratio > trisect_above) return 3;  // rules 1, 2
  if (ratio >= 4) return 2;             // rules 3, 4
  return draw < (ratio - 1.0) / 3.0 ? 2 : 0;  // rule 5
}

IsofacetAreaStats isofacet_area_stats(const std::vector<Isofacet>& facets,
                                      const std::vector<double>& targets,
                                      const std::vector<char>& away) {
  IsofacetAreaStats s;
  s.count = static_cast<int>(facets.size());
  for (std::size_t i = 0; i < facets.size(); ++i) {
    const double ratio = facets[i].area / targets[i];
    const bool far = !away.empty() && away[i];
    s.mean_area += facets[i].area;
    s.max_area = std::max(s.max_area, facets[i].area);
    s.mean_ratio += ratio;
    s.max_ratio = std::max(s.max_ratio, ratio);
    const bool large = facets[i].largest_triangle_area() >= 4 * targets[i];
    s.above_4 += large;
    s.away += far;
    s.above_4_away += far && large;
  }
  if (s.count > 0) {
    s.mean_area /= s.count;
    s.mean_ratio /= s.count;
  }
  return s;
}

IsofacetAreaStats isofacet_area_stats(const Domain& domain, const SizingField& sizing) {
  const std::vector<Isofacet> facets = isofacets(domain.mesh(), domain.f());
  std::vector<char> away;
  const std::vector<double> targets = sizing.target_areas_marking_away(domain, facets, away);
  return isofacet_area_stats(facets, targets, away);
}

bool sizing_met(const IsofacetAreaStats& stats, double max_fraction_above_4) {
  return stats.count > 0 && stats.mean_ratio <= 1.0 &&
         stats.above_4 - stats.above_4_away <= max_fraction_above_4 * (stats.count - stats.away);
}

namespace {

// Collects the points to insert, each once: edge points are keyed by the
// edge and their position along it, face centroids by the face. Points on
// the domain's boundary (its convex hull) are left out, so that the boundary
// sphere stays as initialized.
class RefinementPoints {
 public:
  explicit RefinementPoints(const Domain& domain) : vertices_(domain.vertices()) {
    const auto& tets = domain.tets();
    for (std::size_t t = 0; t < tets.size(); ++t)
      for (int i = 0; i < 4; ++i) {
        if (domain.tet_neighbors()[t][i] >= 0) continue;
        std::array<int, 3> face{tets[t][(i + 1) % 4], tets[t][(i + 2) % 4], tets[t][(i + 3) % 4]};
        std::sort(face.begin(), face.end());
        hull_faces_.insert(face);
        hull_edges_.insert({face[0], face[1]});
        hull_edges_.insert({face[0], face[2]});
        hull_edges_.insert({face[1], face[2]});
      }
  }

  // The point at fraction k/n from the lower-indexed end of edge (a, b).
  void add_edge_point(int a, int b, int k, int n) {
    if (a > b) std::swap(a, b);
    if (hull_edges_.count({a, b})) return;
    if (edge_points_.insert(std::make_tuple(a, b, k, n)).second)
      points_.push_back(vertices_[a] + (static_cast<double>(k) / n) * (vertices_[b] - vertices_[a]));
  }

  void add_face_centroid(std::array<int, 3> face) {
    std::sort(face.begin(), face.end());
    if (hull_faces_.count(face)) return;
    if (faces_.insert(face).second)
      points_.push_back((vertices_[face[0]] + vertices_[face[1]] + vertices_[face[2]]) / 3.0);
  }

  const std::vector<Vec3>& points() const { return points_; }

 private:
  const std::vector<Vec3>& vertices_;
  std::set<std::array<int, 3>> hull_faces_;
  std::set<std::array<int, 2>> hull_edges_;
  std::set<std::tuple<int, int, int, int>> edge_points_;
  std::set<std::array<int, 3>> faces_;
  std::vector<Vec3> points_;
};

// Figure 6b: the two trisection points of each edge and the centroid of each face.
void trisect(const std::array<int, 4>& t, RefinementPoints& out) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      out.add_edge_point(t[i], t[j], 1, 3);
      out.add_edge_point(t[i], t[j], 2, 3);
    }
  for (int i = 0; i < 4; ++i) out.add_face_centroid({t[(i + 1) % 4], t[(i + 2) % 4], t[(i + 3) % 4]});
}

// Figure 6c-d: the midpoint of each edge whose ends have the same sign.
void bisect(const std::array<int, 4>& t, const std::vector<double>& f, RefinementPoints& out) {
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if ((f[t[i]] < 0) == (f[t[j]] < 0)) out.add_edge_point(t[i], t[j], 1, 2);
}

}  // namespace

RefinementStats refine(Domain& domain, const SizingField& sizing, std::mt19937_64& rng) {
  RefinementStats stats;
  const std::vector<Isofacet> facets = isofacets(domain.mesh(), domain.f());
  const std::vector<double> targets = sizing.target_areas(domain, facets);
  detail::poll();  // the run's cancellation
  stats.crossing_tets = static_cast<int>(facets.size());
  stats.before = isofacet_area_stats(facets, targets);

  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  RefinementPoints points(domain);
  for (std::size_t i = 0; i < facets.size(); ++i) {
    // One draw per crossing tet, used or not, so that the sequence of draws
    // does not depend on which tets reach rule 5.
    const double draw = uniform(rng);
    detail::poll_every(i, 4096);  // up to 16 set insertions per tet
    const auto& tet = domain.tets()[facets[i].tet];
    switch (refinement_rule(facets[i], facets[i].area / targets[i], draw)) {
      case 3:
        trisect(tet, points);
        ++stats.trisected;
        break;
      case 2:
        bisect(tet, domain.f(), points);
        ++stats.bisected;
        break;
      default:
        ++stats.left;
    }
  }
  detail::poll();
  stats.inserted_points = static_cast<int>(domain.insert(points.points()).size());
  return stats;
}

}  // namespace pdd
