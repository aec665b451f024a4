// Private to src/solvers: what the three solvers share — the domain's mesh,
// where the samples fall in it, the length unit, the median shift, timing.
#pragma once

#include <pdd/fem.h>
#include <pdd/solvers.h>

#include "solvers/linear_solver.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pdd::detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The samples inside the domain.
struct Problem {
  const TetMesh& mesh;             // domain.mesh(), or *ordered
  std::vector<Location> locations; // tet and barycentric coordinates of each sample
  SparseMatrix Phi;                // sampling matrix, |X| x |V| (empty when skipped)
  std::vector<Vec3> normals;       // the samples' normals scaled to unit length
  double length = 1;               // l: largest side of the samples' bounding box
  std::size_t num_points = 0;
  // With ProblemOptions::spatial_order: the domain's mesh with its vertices
  // renumbered along a Hilbert curve, the tets in the same order; mesh vertex
  // u is domain vertex original[u]. Empty: the domain's own numbering.
  std::unique_ptr<TetMesh> ordered;
  std::vector<int> original;

  // The warm start in mesh's numbering (empty if absent); std::invalid_argument
  // when it does not have one value per vertex.
  Eigen::VectorXd warm_start(const std::vector<double>* values) const;
  // f (in mesh's numbering) in the domain's.
  std::vector<double> domain_values(const Eigen::VectorXd& f) const;

  // Frees the locations, Phi and the normals, for a solver that needs them
  // only to assemble its system (about 110 bytes per sample while it solves).
  void release_samples() {
    std::vector<Location>().swap(locations);
    SparseMatrix().swap(Phi);
    std::vector<Vec3>().swap(normals);
  }
  // Frees the renumbered mesh's tets (the domain's stay), for a solver that
  // needs only its vertices once the system is assembled.
  void release_ordered_tets() {
    if (ordered) std::vector<std::array<int, 4>>().swap(ordered->tets);
  }
};

// The samples' location order (location_order), kept across the solves of a
// run: the samples do not move between them, and sorting 3M takes 0.7 s. It
// is recomputed when the points differ (a hash of their coordinates).
class SampleOrder {
 public:
  const std::vector<std::size_t>& of(const std::vector<Vec3>& points);

 private:
  std::uint64_t key_ = 0;
  std::vector<std::size_t> order_;
};

// Whether make_problem builds Phi: SSD sums its samples' terms from their
// locations alone (add_sample_terms).
enum class SamplingMatrix { kBuild, kSkip };

struct ProblemOptions {
  bool release_triangulation = false;  // free the domain's triangulation once located
  SamplingMatrix phi = SamplingMatrix::kBuild;
  SampleOrder* order = nullptr;  // the solver's, kept across its solves
  // Renumber the mesh's vertices along a Hilbert curve (Problem::ordered): the
  // domain's numbering (each refinement appends its vertices) scatters the
  // neighbours of a vertex across the arrays, and the multigrid solve's
  // products then miss the cache.
  bool spatial_order = false;
};

// Validates the inputs (at least one sample; normals, when required, one per
// point: InputError naming `solver` otherwise) and locates the samples, then
// frees the domain's triangulation if asked (the solve needs only the tets).
Problem make_problem(const Domain& domain, const PointSet& points, const std::string& solver,
                     const std::string& why_normals, const ProblemOptions& options = {});

// The median of the values of f at the samples (Phi f).
double median_at_samples(const SparseMatrix& Phi, const Eigen::VectorXd& f);

// visit(a, b, c) for the three vertices of each face of the domain's convex
// hull (a face of a tet without a neighbour across it).
template <class Visit>
void for_each_hull_face(const Domain& domain, Visit visit) {
  const auto& tets = domain.tets();
  const auto& neighbors = domain.tet_neighbors();
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < 4; ++i)
      if (neighbors[t][i] < 0)
        visit(tets[t][(i + 1) % 4], tets[t][(i + 2) % 4], tets[t][(i + 3) % 4]);
}

// Vertices where f must be positive (outside): those flagged on the domain's
// bounding sphere, or, when none is flagged, those on the convex hull.
std::vector<int> outer_vertices(const Domain& domain);

}  // namespace pdd::detail
