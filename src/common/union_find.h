// Union-find over indices 0..n-1, private to src/.
#pragma once

#include <numeric>
#include <vector>

namespace pdd::detail {

// The root of v in the forest `parent`, halving the path on the way.
inline int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// A forest of n singletons.
inline std::vector<int> singletons(std::size_t n) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  return parent;
}

}  // namespace pdd::detail
