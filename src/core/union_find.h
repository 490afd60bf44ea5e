// conformesh — disjoint sets over 0..n-1 (path halving, no ranks: the sets here are small and
// joined in an order that keeps the trees shallow).
#pragma once

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace conformesh {

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  //! Joins the sets of a and b; the root of b's set becomes the root.
  void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

}  // namespace conformesh
