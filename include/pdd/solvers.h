// The implicit solvers of §3.5: each maps (domain, points) to a
// piecewise-linear function f given at the domain's vertices, whose zero set
// is the reconstructed surface. Sign convention everywhere: f < 0 inside,
// f > 0 outside.
//
// Units. The weights below are dimensionless: lengths are measured in units
// of the input's size l = the largest side of its bounding box (the octree
// implementations of screened Poisson [KH13] and SSD [CT11] in PoissonRecon
// scale the input into a unit cube of side 1.1 l), so that scaling the input
// does not change the surface. The energies are those of Eqs. (13), (15) and (16)-(17) written
// in these units (e.g. SSD's alpha term becomes alpha / (l^2 |X|) sum f(p)^2
// for f in input units).
#pragma once

#include <pdd/domain.h>
#include <pdd/types.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pdd {

enum class SolverKind { kPoisson, kSsd, kSpectral };

// "poisson", "ssd" or "spectral" (any case); InputError otherwise.
SolverKind parse_solver_kind(const std::string& name);
std::string to_string(SolverKind kind);

// Why `kind` needs normals, for the message when a point set has none
// (require_normals): "the SSD solver fits the gradient of f to oriented normals (Eq. 15)".
std::string normals_requirement(SolverKind kind);

// How the sparse symmetric positive definite systems are solved.
enum class LinearMethod {
  kMultigrid,  // conjugate gradients preconditioned by multigrid V-cycles whose coarse levels
               // are the domains of the earlier iterations (the progressive hierarchy, §3.1),
               // from the warm start; systems under direct_below unknowns by CHOLMOD
  kCholmod,    // supernodal Cholesky (CHOLMOD with OpenBLAS) for every system: the reference
};

// "multigrid" or "cholmod" (any case); InputError otherwise.
LinearMethod parse_linear_method(const std::string& name);
std::string to_string(LinearMethod method);

struct LinearSolverOptions {
  LinearMethod method = LinearMethod::kMultigrid;  // see LinearMethod
  std::size_t direct_below = 5000;  // kMultigrid: smaller systems are factored by CHOLMOD
  double cg_tolerance = 1e-6;  // CG stops at |A x - b| <= tol |b|: on the shared data the
                               // surfaces are those of 1e-10 (Chamfer-L1 within 0.5 %, the
                               // same topology) at half the iterations (docs/benchmarks.md)
  int cg_max_iterations = 1000;  // CG gives up (SolverError) after this many iterations
  double max_residual = 1e-6;   // a direct solve whose |A x - b| / |b| exceeds this is a SolverError
  // Multigrid (docs/benchmarks.md, "Multigrid"): Chebyshev smoothing before and after each
  // coarse correction, of degree smoothing_degree on the coarse levels and
  // finest_smoothing_degree on the finest (whose products cost as much as all the coarse
  // levels': fewer per iteration beat the iterations they add); each coarse level has about
  // 1 / coarsening_ratio (>= 1.3) of the vertices of the finer one; levels of coarsest_size
  // vertices or fewer are factored.
  int smoothing_degree = 4;
  int finest_smoothing_degree = 2;
  double coarsening_ratio = 4;
  std::size_t coarsest_size = 2000;
  // The smoother inverts whole the diagonal blocks of unknowns i, j coupled by |a_ij| >
  // block_coupling sqrt(a_ii a_jj) (groups of up to 16, joined strongest first); >= 1 is plain
  // Jacobi. SSD's squared Hessian has such pairs, and its samples' term ties the corners of
  // each sampled tet: without the blocks CG's iterations grow with the domain.
  double block_coupling = 0.3;
};

// Screened Poisson, Eqs. (13)-(14):
//   [L + alpha l / |X| Phi^T Phi] F = Div N~,
// with N~ the normals, each weighted by the inverse of its sampling density, smoothed by a
// Gaussian kernel, then f <- f - median f(p).
struct PoissonOptions {
  bool screened = true;  // false: the original Poisson equation [KBH06] (no alpha term), made
                         // definite by fixing f at one vertex
  double alpha = 0;  // screening weight; 0: ssd_value_weight, from the input's noise, as SSD's
                     // value weight. PoissonRecon's 4 is far too weak here: its degree-2
                     // B-splines place a steep indicator accurately, a linear f on tets of
                     // the sample spacing does not (docs/benchmarks.md, "Poisson's screening")
  double noise = -1;  // sigma of the automatic alpha; < 0: estimate_noise(points) at each solve
  double kernel_size = 0.0;  // standard deviation of the Gaussian that smooths the normals, in
                             // input units; 0 = kernel_spacing x the mean distance from a
                             // sample to its nearest neighbour. The domain should be at least
                             // this fine near the samples (§3.1, "Assumptions Made on the Solver").
  double kernel_spacing = 2.0;  // see kernel_size; about the support of KBH06's splatting
                                // (a node of the sample spacing, smoothed by its B-spline).
                                // Measured with 1% noise: 1 follows the noise (sphere: max
                                // error 0.023), 2 and 3 do not (0.011, 0.008)
  bool median_shift = true;  // f <- f - median f(p) so that the zero set passes through the
                             // samples (§3.5); needed when not screened
};

// Smooth signed distance [CT11], Eq. (15):
//   [alpha/(l^2 |X|) Phi^T Phi + beta/|X| G^T S^T S G + gamma l^2/|T| H^T M~_V^-1 H] F
//     = beta/|X| G^T S^T N,
// with |T| the volume of the domain.
struct SsdOptions {
  double alpha = 0;     // f(p) = 0 at the samples; 0: ssd_value_weight, from the input's noise
  double noise = -1;    // sigma of the automatic alpha; < 0: estimate_noise(points) at each solve
                        // (reconstruct() estimates it once)
  double beta = 1.0;    // grad f(p) = n_p
  double gamma = 0.001;  // Hessian smoothness; larger is smoother (measured on the ellipsoid
                         // of the tests, l = 2: gamma = 1 moves the zero set by up to 0.03,
                         // 0.01 by up to 0.003). On the shared data (docs/benchmarks.md),
                         // 0.001 against 0.01 (alpha = 4000): bunny_clean Chamfer-L1 0.22e-3
                         // vs 0.86e-3, bunny_sparse 1.02e-3 vs 1.42e-3, bunny_noise10 1.54e-3
                         // vs 1.48e-3
};

// The input's noise sigma, in its units: the lower quartile over the points
// of the RMS residual of a cubic height field fitted to each point's
// `neighbors` nearest neighbours (in their principal frame). The lower
// quartile, so that sharp edges and the curvature of sparsely sampled parts,
// whose fits leave larger residuals, do not count as noise. Past 65536 points,
// over every stride-th one of them (their neighbours from all). 0 when the
// input has fewer points than `neighbors`.
double estimate_noise(const PointSet& points, int neighbors = 20);

// SSD's value weight alpha (Eq. 15) for samples of noise sigma whose largest
// bounding-box side is l:
//   alpha = min(K l^2 / sigma^2, kSsdMaxValueWeight),
// the weight of a least-squares fit to data of variance sigma^2. Not in the
// paper, whose SSD takes PoissonRecon's fixed weights (4000 in our units):
// too smooth for clean inputs, whose distance to the truth it doubles, and
// too tight for 0.5-1 % noise (docs/benchmarks.md, "The value weight").
double ssd_value_weight(double noise, double length);
inline constexpr double kSsdValueWeightNoiseScale = 0.035;  // K: the best alpha at 0.5 % and 1 %
                                                            // noise on the shared data
// The cap, for clean inputs. 1e5 is 7 % closer to the truth than 6e4 on the shared data's clean
// inputs, but opens a handle through the fandisk's plate, 1.5 sample spacings thick in its 2k
// samples, on 4 seeds of 10 (6e4 and 4e4: on none of 10).
inline constexpr double kSsdMaxValueWeight = 6e4;

// Spectral [ACTD07], Eqs. (16)-(17): the eigenvector of the largest
// eigenvalue of
//   [G^T S^T C S G] F = lambda [alpha/|X| Phi^T Phi + beta/l L + gamma l L M_V^-1 L + T] F,
// C_p = I + mu n_p n_p^T, each sample's term weighted by the volume of its
// tet over the mean of those volumes (ACTD07's integral of
// grad f^T C grad f; the same as Eq. (17) on a uniform mesh, and immune to
// slivers, see spectral.cpp). T ties f to one value over the domain's outer
// boundary (ours, see outer_tie). The orientation of the normals is ignored.
// The sign of F is chosen so that f > 0 on the boundary of the domain
// (outside). Neither ACTD07 nor the paper gives weights; these are ours,
// measured on the test shapes and the shared data (docs/benchmarks.md, "The
// spectral solver").
struct SpectralOptions {
  double alpha = 0;     // f(p) small at the samples; 0: spectral_value_weight, from the input's
                        // noise. Larger follows the points more closely and their noise too
  double noise = -1;    // sigma of the automatic alpha; < 0: estimate_noise(points) at each solve
  double spacing = -1;  // h of the automatic alpha; < 0: average_spacing(points) at each solve;
                        // 0: no smoothing floor (spectral_value_weight)
  double beta = 0.0;    // Dirichlet energy in the constraint (no measured benefit)
  double gamma = 1.0;   // bi-Laplacian energy in the constraint (ACTD07's smoothness)
  double mu = 10.0;     // anisotropy: gradients along n_p count 1 + mu times more. Measured on
                        // the test shapes: 0 to 100 give the same clean surfaces (the data term
                        // places the zero set); with 1% noise larger mu is slightly smoother
  double outer_tie = 1.0;     // weight of sum (f_i - f_j)^2 over the edges of the domain's outer
                              // boundary, relative to the constraint's diagonal there (0: none).
                              // The outside is one region: without the tie, thin parts (ears, a
                              // base) came out as open sheets running to the boundary
  int max_iterations = 2000;  // LOBPCG iterations before SolverError
  double tolerance = 1e-6;    // |A f - lambda B f| / (lambda |B f|) of the eigenpair. 1e-8: the
                              // same distances on the shared data, 1.15x the time
  bool median_shift = true;   // f <- f - median f(p) after signing, as ACTD07 picks the
                              // isovalue at the median of f over the samples
};

// The spectral solver's alpha for samples of noise sigma and average spacing
// h, largest bounding-box side l: min(K (l / s)^3, kSpectralMaxValueWeight),
// where l alpha^(-1/3) is about the length s over which the bi-Laplacian
// smooths them. s = sigma, but at least F h from sigma = r1 h on (ramped from
// r0 h): noise interpolated there leaves bumps at the spacing that each
// refinement resolves anew. K and the cap: the bunny at 0, 0.5 and 1 % noise;
// r0, r1, F: virtual scans (docs/benchmarks.md, "The spectral solver").
double spectral_value_weight(double noise, double spacing, double length);
inline constexpr double kSpectralValueWeightNoiseScale = 0.65;
inline constexpr double kSpectralMaxValueWeight = 1e9;  // 1e10 is no closer, and slower
inline constexpr double kSpectralSmoothedNoise[2] = {0.08, 0.16};  // r0, r1: sigma / h
inline constexpr double kSpectralSmoothingSpacings = 0.45;          // F

struct SolverOptions {
  SolverKind kind = SolverKind::kSsd;  // the paper's experiments use SSD (§4)
  PoissonOptions poisson;
  SsdOptions ssd;
  SpectralOptions spectral;
  LinearSolverOptions linear;
};

// What the last solve did.
struct SolverStats {
  std::string method;            // "cholmod" or "cg+multigrid"; spectral: "lobpcg+" one of them
  int iterations = 0;            // CG iterations (0 for CHOLMOD); spectral: LOBPCG iterations,
                                 // each with one V-cycle (or exact solve) with B
  int levels = 0;                // multigrid levels, the system's included (1: direct)
  double residual = 0;           // |A x - b| / |b| of the final solve (spectral: of the eigenpair,
                                 // |A x - lambda B x| / (lambda |B x|))
  double assembly_seconds = 0;   // point location, operators and system matrix (and SSD's
                                 // noise estimate when SsdOptions::noise asks for one)
  double factorize_seconds = 0;  // CHOLMOD's factorization, or the multigrid's set-up (coarse
                                 // levels, Galerkin operators, smoother bounds)
  double solve_seconds = 0;      // triangular solves / CG / LOBPCG, and the median shift
  std::size_t num_vertices = 0;
  std::size_t num_points = 0;
  std::size_t nonzeros = 0;      // in the system matrix (lower and upper)
  double median_shift = 0;       // the constant subtracted from f (0 when not shifted)
  double eigenvalue = 0;         // spectral: lambda
  double kernel_size = 0;        // Poisson: the kernel standard deviation used, in input units
  double value_weight = 0;       // SSD, screened Poisson and spectral: the alpha solved with
                                 // (ssd_value_weight or spectral_value_weight when automatic)
};

class ImplicitSolver {
 public:
  virtual ~ImplicitSolver();
  // f at the vertices of `domain` (f < 0 inside). warm_start, if given, is a
  // guess of f at the same vertices (e.g. the previous iterate interpolated
  // onto the new domain); CG and the spectral solver's LOBPCG start from it. A solver called on a
  // sequence of domains, each refined from the last (vertex i of one is
  // vertex i of the next, as Domain::insert and the optimizer keep them),
  // uses the earlier ones as the coarse levels of its multigrid. Throws InputError
  // when a point lies outside the domain or normals are missing, SolverError
  // when the numerical solve fails (never returns an unconverged f).
  virtual std::vector<double> solve(const Domain& domain, const PointSet& points,
                                    const std::vector<double>* warm_start = nullptr) = 0;
  virtual const SolverStats& stats() const = 0;
  // The next solve frees the domain's triangulation once it has located the
  // samples (Domain::release_triangulation): a solve's system and multigrid
  // are the peak of a run's memory, and the triangulation comes back, rebuilt
  // from the tets, when it is next needed.
  void release_triangulation_in_next_solve() { release_triangulation_ = true; }
  // Poisson and SSD need oriented normals, spectral needs normals but not
  // their orientation; all three throw InputError without normals.
  virtual bool needs_normals() const = 0;
  virtual bool needs_oriented_normals() const = 0;

 protected:
  // Asked for by release_triangulation_in_next_solve; the next solve takes it.
  bool take_release_triangulation() { return std::exchange(release_triangulation_, false); }

 private:
  bool release_triangulation_ = false;
};

std::unique_ptr<ImplicitSolver> make_solver(const SolverOptions& options);

// A sparse symmetric system A f = b.
struct LinearSystem {
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b;
};

// The system of Eq. (15) that the SSD solver solves, for studies of its
// conditioning (Table 2). Same errors as the solver's solve().
LinearSystem ssd_system(const Domain& domain, const PointSet& points,
                        const SsdOptions& options = {});

// Table 2's measure of the domain's conditioning: plain conjugate gradients
// (Jacobi preconditioner) from 0 to a relative residual of 1e-10 on the SSD
// system with alpha = beta = 1, gamma = 0.1, a Hessian-dominated system whose
// conditioning follows the shape of the tets.
struct ConditioningProbe {
  long iterations = 0;
  double residual = 0;  // |A f - b| / |b| at the end
  double seconds = 0;   // CG alone (setup and iterations), not the assembly
  bool converged = false;
};
ConditioningProbe ssd_conditioning_probe(const Domain& domain, const PointSet& points);

}  // namespace pdd
