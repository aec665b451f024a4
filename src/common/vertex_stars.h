// The tets around each vertex of a tet mesh, and its closed one-rings.
// Private to src/ (the FEM assembly and the optimizer's quadratic).
#pragma once

#include <pdd/types.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "common/cancellation.h"

namespace pdd::detail {

// Vertex -> incident tets, in increasing tet order (compressed rows).
struct VertexStars {
  std::vector<int> offsets;  // |V| + 1
  std::vector<int> tets;
  int begin(int v) const { return offsets[v]; }
  int end(int v) const { return offsets[v + 1]; }
};

inline VertexStars vertex_stars(const TetMesh& mesh) {
  VertexStars s;
  const int n = static_cast<int>(mesh.vertices.size());
  s.offsets.assign(n + 1, 0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    for (int v : mesh.tets[t]) {
      if (v < 0 || v >= n)
        throw std::invalid_argument("tet mesh: a tet refers to a missing vertex");
      ++s.offsets[v + 1];
    }
    poll_every(t);  // the run's cancellation
  }
  for (int v = 0; v < n; ++v) s.offsets[v + 1] += s.offsets[v];
  s.tets.resize(s.offsets[n]);
  std::vector<int> fill(s.offsets.begin(), s.offsets.end() - 1);
  for (int t = 0; t < static_cast<int>(mesh.tets.size()); ++t) {
    for (int v : mesh.tets[t]) s.tets[fill[v]++] = t;
    poll_every(t);
  }
  return s;
}

inline int local_index(const std::array<int, 4>& tet, int v) {
  for (int i = 0; i < 4; ++i)
    if (tet[i] == v) return i;
  return -1;
}

// One table of n ints per thread, -1 at first: markers or positions by
// vertex for tasks that visit vertices one at a time.
using PerThreadTable = tbb::enumerable_thread_specific<std::vector<int>>;
inline PerThreadTable per_thread_table(int n) {
  return PerThreadTable([n] { return std::vector<int>(n, -1); });
}

// The closed one-ring of every vertex (v and its neighbours, sorted),
// computed in parallel. Each neighbour is taken once, through a marker per
// thread, so that only the ring itself (about 15 vertices) is sorted, not
// the 4 corners of each of the ~24 tets around v.
inline std::vector<std::vector<int>> one_rings(const TetMesh& mesh, const VertexStars& stars) {
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<std::vector<int>> rings(n);
  PerThreadTable markers = per_thread_table(n);
  polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    std::vector<int>& marker = markers.local();
    for (int v = r.begin(); v < r.end(); ++v) {
      std::vector<int>& ring = rings[v];
      for (int k = stars.begin(v); k < stars.end(v); ++k)
        for (int w : mesh.tets[stars.tets[k]])
          if (marker[w] != v) {
            marker[w] = v;
            ring.push_back(w);
          }
      std::sort(ring.begin(), ring.end());
    }
  });
  return rings;
}

}  // namespace pdd::detail
