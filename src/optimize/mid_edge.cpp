// The mid-edge term of §3.3, Eq. (8): in each tet crossed by the isosurface,
// the midpoint of every crossing edge is pulled onto the plane of the
// isofacet a_t, along its normal.
#include "optimize/energy_terms.h"

#include <pdd/isofacet.h>

#include <cmath>

namespace pdd::optimize_detail {

void add_mid_edge_term(const Domain& domain, double weight_scale, QuadraticAccumulator& q) {
  // p_e, n_{a_t} and area(a_t) are constants of the round.
  const std::vector<Isofacet> facets = isofacets(domain.mesh(), domain.f());
  for (const Isofacet& a : facets) {
    // A flat tet has no gradient, hence no plane: it adds nothing.
    if (!a.normal.allFinite() || !(a.area > 0) || !std::isfinite(a.area)) continue;
    const double w = weight_scale * a.area;  // w_m(t) = area(a_t) / r(T)^2
    const Vec3& n = a.normal;
    for (int k = 0; k < a.num_corners; ++k) {
      // ((v_e1 + v_e2) / 2 - p_e) . n = g^T x - s with g = n/2 on both ends.
      const int e[2] = {a.edges[k][0], a.edges[k][1]};
      const double s = n.dot(a.corners[k]);
      const Eigen::Matrix3d nn = (w * 0.25) * n * n.transpose();
      for (int u = 0; u < 2; ++u) {
        q.b.segment<3>(3 * e[u]) += w * 0.5 * s * n;
        for (int v = 0; v < 2; ++v) q.add_coupled(e[u], e[v], nn);
      }
      q.c += w * s * s;
    }
  }
}

}  // namespace pdd::optimize_detail
