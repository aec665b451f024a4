// The mid-edge term of §3.3, Eq. (8): in each tet crossed by the isosurface,
// the midpoint of every crossing edge is pulled onto the plane of the
// isofacet a_t, along its normal.
#include "optimize/energy_terms.h"

#include <pdd/isofacet.h>

#include <array>
#include <cmath>

namespace pdd::optimize_detail {

namespace {

// What the term reads of an isofacet a_t: its normal, its area, and n . p_e
// and the edge of each corner (about half an Isofacet's bytes: the facets of
// a 1M run's domain were its peak of memory).
struct Plane {
  Vec3 normal;
  double area = 0;
  std::array<double, 4> offset;
  std::array<std::array<int, 2>, 4> edges;
  int corners = 0;
};

}  // namespace

void add_mid_edge_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q) {
  // p_e, n_{a_t} and area(a_t) are constants of the round. A flat tet has no
  // gradient, hence no plane: it adds nothing.
  const TetMesh& mesh = domain.mesh();
  const std::vector<double>& f = domain.f();
  std::vector<int> facet_of_tet(domain.num_tets(), -1);
  detail::polled_parallel_for(facet_of_tet.size(), [&](std::size_t t) {
    if (crosses_isovalue(mesh, f, static_cast<int>(t))) facet_of_tet[t] = 0;
  });
  int count = 0;
  for (int& k : facet_of_tet)
    if (k == 0) k = count++;
  std::vector<Plane> planes(count);
  detail::polled_parallel_for(facet_of_tet.size(), [&](std::size_t t) {
    Isofacet a;
    if (facet_of_tet[t] < 0 || !isofacet(mesh, f, static_cast<int>(t), a)) return;
    if (!(a.normal.allFinite() && a.area > 0 && std::isfinite(a.area))) {
      facet_of_tet[t] = -1;
      return;
    }
    Plane& plane = planes[facet_of_tet[t]];
    plane.normal = a.normal;
    plane.area = a.area;
    plane.corners = a.num_corners;
    for (int c = 0; c < a.num_corners; ++c) {
      plane.offset[c] = a.normal.dot(a.corners[c]);
      plane.edges[c] = a.edges[c];
    }
  });
  // Per crossing edge e of a_t, ((v_e1 + v_e2) / 2 - p_e) . n = g^T x - s with
  // g = n/2 on both ends: w (g^T x - s)^2 adds w n n^T / 4 to the blocks of
  // both ends and w s n / 2 to b at both ends. w_m(t) = area(a_t) / r(T)^2.
  const detail::VertexStars& stars = q.stars();
  q.add_coupled_by_columns([&](int j, auto add, bool adding) {
    for (int i = stars.begin(j); i < stars.end(j); ++i) {
      const int k = facet_of_tet[stars.tets[i]];
      if (k < 0) continue;
      const Plane& a = planes[k];
      const double w = weight_scale * a.area;
      const Eigen::Matrix3d nn = (w * 0.25) * a.normal * a.normal.transpose();
      for (int c = 0; c < a.corners; ++c) {
        const auto& e = a.edges[c];
        if (e[0] != j && e[1] != j) continue;
        add(e[0], nn);
        add(e[1], nn);
        if (adding) q.b.segment<3>(3 * j) += w * 0.5 * a.offset[c] * a.normal;
      }
    }
  });
  for (std::size_t t = 0; t < facet_of_tet.size(); ++t) {
    if (facet_of_tet[t] < 0) continue;
    const Plane& a = planes[facet_of_tet[t]];
    const double w = weight_scale * a.area;
    for (int c = 0; c < a.corners; ++c) q.c += w * a.offset[c] * a.offset[c];
  }
}

}  // namespace pdd::optimize_detail
