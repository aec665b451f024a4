// Removal of components below the output's resolution (contour.h).
#include <pdd/contour.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace pdd {
namespace {

// Union-find root of v, halving the path on the way.
int root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

SmallComponentsReport remove_small_components(TriangleMesh& mesh, double min_edges) {
  if (!(min_edges >= 0) || !std::isfinite(min_edges))
    throw std::invalid_argument("remove_small_components: min_edges must be >= 0, got " +
                                std::to_string(min_edges));
  SmallComponentsReport report;
  if (min_edges == 0 || mesh.faces.empty()) return report;

  const auto& x = mesh.vertices;
  std::vector<int> parent(x.size());
  std::iota(parent.begin(), parent.end(), 0);
  double edge_sum = 0;
  for (const auto& f : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      edge_sum += (x[f[i]] - x[f[(i + 1) % 3]]).norm();
      parent[root(parent, f[i])] = root(parent, f[(i + 1) % 3]);
    }
  const double min_diagonal = min_edges * edge_sum / (3.0 * static_cast<double>(mesh.faces.size()));

  // Per root: its faces and bounding box.
  std::vector<int> faces(x.size(), 0);
  std::vector<Eigen::AlignedBox3d> box(x.size());
  for (const auto& f : mesh.faces) {
    const int r = root(parent, f[0]);
    ++faces[r];
    for (int v : f) box[r].extend(x[v]);
  }
  const int largest = static_cast<int>(std::max_element(faces.begin(), faces.end()) - faces.begin());
  std::vector<char> small(x.size(), 0);
  for (std::size_t r = 0; r < x.size(); ++r)
    if (faces[r] > 0 && static_cast<int>(r) != largest && box[r].diagonal().norm() < min_diagonal) {
      small[r] = 1;
      ++report.components;
      report.faces += faces[r];
    }
  if (report.components == 0) return report;

  TriangleMesh kept;
  std::vector<int> index(x.size(), -1);
  for (const auto& f : mesh.faces)
    if (!small[root(parent, f[0])])
      for (int v : f) index[v] = 0;
  for (std::size_t v = 0; v < x.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int>(kept.vertices.size());
      kept.vertices.push_back(x[v]);
    }
  for (const auto& f : mesh.faces)
    if (!small[root(parent, f[0])]) kept.faces.push_back({index[f[0]], index[f[1]], index[f[2]]});
  mesh = std::move(kept);
  return report;
}

}  // namespace pdd
