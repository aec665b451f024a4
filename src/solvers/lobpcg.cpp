#include "solvers/lobpcg.h"

#include "common/cancellation.h"
#include "common/parallel_kernels.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

namespace pdd::detail {
namespace {

// Vectors of a search space with their images under A and B.
struct Basis {
  std::vector<const Eigen::VectorXd*> v, av, bv;
  void add(const Eigen::VectorXd& x, const Eigen::VectorXd& ax, const Eigen::VectorXd& bx) {
    v.push_back(&x);
    av.push_back(&ax);
    bv.push_back(&bx);
  }
  int size() const { return static_cast<int>(v.size()); }
};

// Rayleigh-Ritz: the coefficients c (in the basis) of the vector of largest
// Rayleigh quotient in the span, with c^T (S^T B S) c = 1. Directions that are
// numerically dependent in the B inner product are dropped rather than
// inverted. Returns the quotient.
double rayleigh_ritz(const Basis& s, Eigen::VectorXd& c) {
  const int m = s.size();
  Eigen::MatrixXd ga(m, m), gb(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = i; j < m; ++j) {
      ga(i, j) = ga(j, i) = deterministic_dot(*s.v[i], *s.av[j]);
      gb(i, j) = gb(j, i) = deterministic_dot(*s.v[i], *s.bv[j]);
    }
  // Q = V D^-1/2 over the well-conditioned eigenvectors of S^T B S.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> b_eig(gb);
  const Eigen::VectorXd& d = b_eig.eigenvalues();
  const double largest = d.maxCoeff();
  int kept = 0;
  for (int i = 0; i < m; ++i)
    if (d[i] > 1e-12 * largest) ++kept;
  Eigen::MatrixXd q(m, kept);
  for (int i = 0, k = 0; i < m; ++i)
    if (d[i] > 1e-12 * largest) q.col(k++) = b_eig.eigenvectors().col(i) / std::sqrt(d[i]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> a_eig(q.transpose() * ga * q);
  c = q * a_eig.eigenvectors().col(kept - 1);  // eigenvalues increase
  return a_eig.eigenvalues()[kept - 1];
}

// y = sum of c_i * vectors[i].
void combine(const std::vector<const Eigen::VectorXd*>& vectors, const Eigen::VectorXd& c,
             int first, Eigen::VectorXd& y) {
  const Eigen::Index n = vectors[0]->size();
  Eigen::VectorXd out(n);
  for_blocks(n, [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index k = begin; k < end; ++k) {
      double sum = 0;
      for (int i = first; i < static_cast<int>(vectors.size()); ++i) sum += c[i] * (*vectors[i])[k];
      out[k] = sum;
    }
  });
  y.swap(out);
}

// v, Av and Bv scaled to v^T B v = 1.
void normalize(Eigen::VectorXd& v, Eigen::VectorXd& av, Eigen::VectorXd& bv) {
  const double norm = std::sqrt(deterministic_dot(v, bv));
  if (!(norm > 0)) return;
  v /= norm;
  av /= norm;
  bv /= norm;
}

}  // namespace

LobpcgResult largest_eigenpair(
    const SymmetricProduct<double>& A, const SymmetricProduct<double>& B,
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& precondition,
    Eigen::VectorXd& x, double tolerance, int max_iterations) {
  const Eigen::Index n = A.matrix().rows();
  if (x.size() != n || !x.allFinite() || x.squaredNorm() == 0) {
    // No start given: a fixed pseudo-random one, so that runs repeat.
    std::mt19937 random(1);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    x.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = uniform(random);
  }
  Eigen::VectorXd ax, bx, w, aw, bw, p, ap, bp, r, c;
  A(x, ax);
  B(x, bx);
  LobpcgResult result;
  {
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
    Eigen::VectorXd a1, b1;
    A(ones, a1);
    B(ones, b1);
    Basis start;
    start.add(x, ax, bx);
    start.add(ones, a1, b1);
    result.eigenvalue = rayleigh_ritz(start, c);
    combine(start.v, c, 0, w);
    combine(start.av, c, 0, aw);
    combine(start.bv, c, 0, bw);
    x.swap(w);
    ax.swap(aw);
    bx.swap(bw);
  }
  double lambda = result.eigenvalue;
  for (int it = 0;; ++it) {
    if (it % 10 == 0 && it > 0) {  // the recurrences' rounding, reset
      A(x, ax);
      B(x, bx);
      const double xbx = deterministic_dot(x, bx);
      lambda = deterministic_dot(x, ax) / xbx;
      const double scale = 1 / std::sqrt(xbx);
      x *= scale;
      ax *= scale;
      bx *= scale;
    }
    r = ax - lambda * bx;
    result.iterations = it;
    result.residual = r.norm() / (std::abs(lambda) * bx.norm());
    if (result.residual <= tolerance || it >= max_iterations) break;
    poll();  // the run's cancellation
    precondition(r, w);
    // w B-orthogonal to x and of unit B-norm, p of unit B-norm: a Gram matrix
    // near the identity, whose small eigenvalues are real dependence and not
    // the scale of a converging step.
    w -= deterministic_dot(w, bx) * x;
    A(w, aw);
    B(w, bw);
    normalize(w, aw, bw);
    if (p.size() == n) normalize(p, ap, bp);
    Basis s;
    s.add(x, ax, bx);
    s.add(w, aw, bw);
    if (p.size() == n) s.add(p, ap, bp);
    lambda = rayleigh_ritz(s, c);
    // The new search direction: the part of the step outside x.
    Eigen::VectorXd np, nap, nbp;
    combine(s.v, c, 1, np);
    combine(s.av, c, 1, nap);
    combine(s.bv, c, 1, nbp);
    x = c[0] * x + np;
    ax = c[0] * ax + nap;
    bx = c[0] * bx + nbp;
    p.swap(np);
    ap.swap(nap);
    bp.swap(nbp);
  }
  A(x, ax);
  B(x, bx);
  const double xbx = deterministic_dot(x, bx);
  lambda = deterministic_dot(x, ax) / xbx;
  x /= std::sqrt(xbx);
  bx /= std::sqrt(xbx);
  ax /= std::sqrt(xbx);
  result.eigenvalue = lambda;
  result.residual = (ax - lambda * bx).norm() / (std::abs(lambda) * bx.norm());
  result.converged = result.residual <= tolerance && x.allFinite();
  return result;
}

}  // namespace pdd::detail
