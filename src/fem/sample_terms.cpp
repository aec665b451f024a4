// The samples' terms of Eq. (15), G^T S^T S G, Phi^T Phi and G^T S^T N, summed
// from the tets that hold samples into a matrix's existing pattern: neither
// Phi (4 entries per sample, built from triplets) nor a product with it is
// formed, and nothing is visited per unsampled tet but its sample count.
#include <pdd/fem.h>

#include "common/cancellation.h"
#include "fem/assembly.h"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace pdd {
namespace {

// What a sampled tet contributes: its sample count, the sum of its samples'
// normals and their barycentric moments sum_p b(p) b(p)^T (upper triangle).
struct SampledTet {
  int tet;
  double count;
  Vec3 normal_sum;
  double moment[10];
};

inline int moment_slot(int i, int j) {
  if (i > j) std::swap(i, j);
  return i * 4 - i * (i - 1) / 2 + (j - i);  // rows 0..3 of the upper triangle: 4, 3, 2, 1
}

}  // namespace

Eigen::VectorXd add_sample_terms(SparseMatrix& A, const TetMesh& mesh,
                                 const std::vector<Location>& locations,
                                 const std::vector<Vec3>& normals, double gradient_weight,
                                 double value_weight, Stored stored) {
  const int n = static_cast<int>(mesh.vertices.size());
  const std::size_t nt = mesh.tets.size();
  if (A.rows() != n || A.cols() != n || !A.isCompressed())
    throw std::invalid_argument("add_sample_terms: A must be a compressed |V| x |V| matrix");
  if (normals.size() != locations.size())
    throw std::invalid_argument("add_sample_terms: one normal per sample is required");
  // The samples grouped by tet, each group in increasing sample order.
  std::vector<int> first(nt + 1, 0);
  std::size_t num_sampled = 0;
  for (std::size_t p = 0; p < locations.size(); ++p) {
    const int t = locations[p].tet;
    if (t < 0 || static_cast<std::size_t>(t) >= nt)
      throw std::invalid_argument("add_sample_terms: sample " + std::to_string(p + 1) +
                                  " is not located in the mesh");
    num_sampled += first[static_cast<std::size_t>(t) + 1]++ == 0;
  }
  // Reserved to size: grown by doubling, the copy would hold up to 3x its
  // 128 bytes per sampled tet for a moment (380 MB at 3M samples).
  std::vector<SampledTet> sampled;
  sampled.reserve(num_sampled);
  for (std::size_t t = 0; t < nt; ++t) {
    if (first[t + 1] > 0)
      sampled.push_back({static_cast<int>(t), static_cast<double>(first[t + 1]), Vec3::Zero(), {}});
    first[t + 1] += first[t];
    detail::poll_every(t);  // the run's cancellation
  }
  std::vector<int> by_tet(locations.size());
  {
    std::vector<int> cursor(first.begin(), first.end() - 1);
    for (std::size_t p = 0; p < locations.size(); ++p)
      by_tet[static_cast<std::size_t>(cursor[locations[p].tet]++)] = static_cast<int>(p);
  }
  detail::polled_parallel_for(sampled.size(), [&](std::size_t k) {
    SampledTet& s = sampled[k];
    for (int q = first[s.tet]; q < first[s.tet + 1]; ++q) {
      const std::size_t p = static_cast<std::size_t>(by_tet[q]);
      const auto& b = locations[p].barycentric;
      s.normal_sum += normals[p];
      for (int i = 0; i < 4; ++i)
        for (int j = i; j < 4; ++j) s.moment[moment_slot(i, j)] += b[i] * b[j];
    }
  });
  std::vector<int>().swap(first);
  std::vector<int>().swap(by_tet);

  // The sampled tets around each vertex, in increasing tet order.
  std::vector<long long> offsets(static_cast<std::size_t>(n) + 1, 0);
  for (const SampledTet& s : sampled)
    for (int v : mesh.tets[s.tet]) ++offsets[static_cast<std::size_t>(v) + 1];
  for (int v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<int> star(static_cast<std::size_t>(offsets[n]));
  {
    std::vector<long long> cursor(offsets.begin(), offsets.end() - 1);
    for (std::size_t k = 0; k < sampled.size(); ++k)
      for (int v : mesh.tets[sampled[k].tet])
        star[static_cast<std::size_t>(cursor[v]++)] = static_cast<int>(k);
  }
  detail::poll();

  const bool lower = stored == Stored::kLower;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  Eigen::VectorXd normal_term = Eigen::VectorXd::Zero(n);
  detail::polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& range) {
    // Column j's two sums per row (its rows: the vertices of the sampled
    // tets around j, a few dozen), each in increasing tet order.
    struct Sums {
      int row;
      double gradient, value;
    };
    std::vector<Sums> sums;
    for (int j = range.begin(); j < range.end(); ++j) {
      sums.clear();
      double normal_sum = 0;
      for (long long e = offsets[j]; e < offsets[j + 1]; ++e) {
        const SampledTet& s = sampled[static_cast<std::size_t>(star[static_cast<std::size_t>(e)])];
        const auto& tet = mesh.tets[s.tet];
        const detail::TetGradients g = detail::tet_gradients(mesh, s.tet);
        const int jl = detail::local_index(tet, j);
        normal_sum += g.grad[jl].dot(s.normal_sum);
        const Vec3 wj = s.count * g.grad[jl];
        for (int i = 0; i < 4; ++i) {
          const int row = tet[i];
          if (lower && row < j) continue;
          std::size_t k = 0;
          while (k < sums.size() && sums[k].row != row) ++k;
          if (k == sums.size()) sums.push_back({row, 0.0, 0.0});
          sums[k].gradient += g.grad[i].dot(wj);
          sums[k].value += s.moment[moment_slot(i, jl)];
        }
      }
      normal_term[j] = normal_sum;
      const int* begin = inner + outer[j];
      const int* end = inner + outer[j + 1];
      for (const Sums& s : sums) {
        const int* at = std::lower_bound(begin, end, s.row);
        if (at == end || *at != s.row)
          throw std::logic_error("add_sample_terms: A's pattern misses an entry");
        values[at - inner] += gradient_weight * s.gradient + value_weight * s.value;
      }
    }
  });
  return normal_term;
}

}  // namespace pdd
