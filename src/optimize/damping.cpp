// The damping term of §3.3, Eqs. (9)-(10): vertices whose f lies outside the
// range seen around the isosurface are held towards their old position, the
// more so the further f is from that range.
#include "optimize/energy_terms.h"

#include <algorithm>
#include <limits>

namespace pdd::optimize_detail {

// Eq. (9).
std::vector<double> damping_factors(const Domain& domain) {
  const auto& f = domain.f();
  std::vector<double> g(f.size(), 0.0);
  if (f.empty()) return g;
  const double f_min = *std::min_element(f.begin(), f.end());
  const double f_max = *std::max_element(f.begin(), f.end());
  // f_min^S, f_max^S: over the vertices of the tets crossing S (f < 0 on one
  // vertex, f >= 0 on another).
  double fs_min = std::numeric_limits<double>::infinity();
  double fs_max = -fs_min;
  const auto& tets = domain.tets();
  for (std::size_t k = 0; k < tets.size(); ++k) {
    detail::poll_every(k);  // the run's cancellation
    const auto& t = tets[k];
    int negative = 0;
    for (int v : t) negative += f[v] < 0;
    if (negative == 0 || negative == 4) continue;
    for (int v : t) {
      fs_min = std::min(fs_min, f[v]);
      fs_max = std::max(fs_max, f[v]);
    }
  }
  if (fs_min > fs_max) return g;  // no isosurface: nothing to stay close to
  for (std::size_t v = 0; v < f.size(); ++v) {
    if (f[v] < fs_min)
      g[v] = (f[v] - fs_min) / (f_min - fs_min);
    else if (f[v] > fs_max)
      g[v] = (f[v] - fs_max) / (f_max - fs_max);
  }
  return g;
}

// Eq. (10): weight * g_d(v) * |v - v~|^2, v~ the position before the round.
void add_damping_term(const Domain& domain, const std::vector<bool>& fixed, double weight,
                      QuadraticAccumulator& q) {
  const std::vector<double> g = damping_factors(domain);
  const auto& x = domain.vertices();
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (fixed[v] || g[v] == 0) continue;
    const double w = weight * g[v];
    q.add_isotropic(static_cast<int>(v), static_cast<int>(v), w);
    q.b.segment<3>(3 * v) += w * x[v];
    q.c += w * x[v].squaredNorm();
  }
}

}  // namespace pdd::optimize_detail
