// The tets around each vertex of a tet mesh, and its closed one-rings.
// Private to src/ (the FEM assembly and the optimizer's quadratic).
#pragma once

#include <pdd/types.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
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

// A vertex's closed one-ring: a sorted range of OneRings' array.
struct Ring {
  const int* first;
  const int* last;
  const int* begin() const { return first; }
  const int* end() const { return last; }
  std::size_t size() const { return static_cast<std::size_t>(last - first); }
  int operator[](std::size_t k) const { return first[k]; }
};

// The closed one-ring of every vertex (v and its neighbours, sorted), in
// compressed rows: one array for all, not a vector per vertex (at 1.6M
// vertices, 8M allocations under one malloc arena, and twice the memory).
struct OneRings {
  std::vector<int> offsets;  // |V| + 1
  std::vector<int> vertices;
  Ring operator[](int v) const {
    return {vertices.data() + offsets[v], vertices.data() + offsets[v + 1]};
  }
};

// Computed in parallel: each neighbour is taken once, through a marker per
// thread, so that only the ring itself (about 15 vertices) is sorted, not
// the 4 corners of each of the ~24 tets around v. One pass counts, one fills.
inline OneRings one_rings(const TetMesh& mesh, const VertexStars& stars) {
  const int n = static_cast<int>(mesh.vertices.size());
  OneRings rings;
  rings.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  PerThreadTable markers = per_thread_table(n);
  // Visits each vertex of v's ring once; the marker of pass p at v is 2v + p.
  auto for_ring = [&](std::vector<int>& marker, int v, int pass, auto&& visit) {
    for (int k = stars.begin(v); k < stars.end(v); ++k)
      for (int w : mesh.tets[stars.tets[k]])
        if (marker[w] != 2 * v + pass) {
          marker[w] = 2 * v + pass;
          visit(w);
        }
  };
  polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    std::vector<int>& marker = markers.local();
    for (int v = r.begin(); v < r.end(); ++v) {
      int count = 0;
      for_ring(marker, v, 0, [&](int) { ++count; });
      rings.offsets[v + 1] = count;
    }
  });
  long long total = 0;
  for (int v = 0; v < n; ++v) {
    total += rings.offsets[v + 1];
    if (total > std::numeric_limits<int>::max())
      throw std::length_error("tet mesh: the one-rings hold more entries than an int can index");
    rings.offsets[v + 1] = static_cast<int>(total);
  }
  rings.vertices.resize(static_cast<std::size_t>(total));
  polled_parallel_ranges(n, [&](const tbb::blocked_range<int>& r) {
    std::vector<int>& marker = markers.local();
    for (int v = r.begin(); v < r.end(); ++v) {
      int* out = rings.vertices.data() + rings.offsets[v];
      int* fill = out;
      for_ring(marker, v, 1, [&](int w) { *fill++ = w; });
      std::sort(out, fill);
    }
  });
  return rings;
}

}  // namespace pdd::detail
