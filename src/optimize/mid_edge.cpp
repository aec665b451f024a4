// The mid-edge term of §3.3, Eq. (8): in each tet crossed by the isosurface,
// the midpoint of every crossing edge is pulled onto the plane of the
// isofacet a_t, along its normal.
#include "optimize/energy_terms.h"

#include <pdd/isofacet.h>

#include <cmath>

namespace pdd::optimize_detail {

void add_mid_edge_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q) {
  // p_e, n_{a_t} and area(a_t) are constants of the round. A flat tet has no
  // gradient, hence no plane: it adds nothing.
  const std::vector<Isofacet> facets = isofacets(domain.mesh(), domain.f());
  std::vector<int> facet_of_tet(domain.num_tets(), -1);
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const Isofacet& a = facets[k];
    if (a.normal.allFinite() && a.area > 0 && std::isfinite(a.area))
      facet_of_tet[a.tet] = static_cast<int>(k);
  }
  // Per crossing edge e of a_t, ((v_e1 + v_e2) / 2 - p_e) . n = g^T x - s with
  // g = n/2 on both ends: w (g^T x - s)^2 adds w n n^T / 4 to the blocks of
  // both ends and w s n / 2 to b at both ends. w_m(t) = area(a_t) / r(T)^2.
  const detail::VertexStars& stars = q.stars();
  q.add_coupled_by_columns([&](int j, auto add, bool adding) {
    for (int i = stars.begin(j); i < stars.end(j); ++i) {
      const int k = facet_of_tet[stars.tets[i]];
      if (k < 0) continue;
      const Isofacet& a = facets[k];
      const double w = weight_scale * a.area;
      const Eigen::Matrix3d nn = (w * 0.25) * a.normal * a.normal.transpose();
      for (int c = 0; c < a.num_corners; ++c) {
        const auto& e = a.edges[c];
        if (e[0] != j && e[1] != j) continue;
        add(e[0], nn);
        add(e[1], nn);
        if (adding) q.b.segment<3>(3 * j) += w * 0.5 * a.normal.dot(a.corners[c]) * a.normal;
      }
    }
  });
  for (const Isofacet& a : facets) {
    if (facet_of_tet[a.tet] < 0) continue;
    const double w = weight_scale * a.area;
    for (int c = 0; c < a.num_corners; ++c) {
      const double s = a.normal.dot(a.corners[c]);
      q.c += w * s * s;
    }
  }
}

}  // namespace pdd::optimize_detail
