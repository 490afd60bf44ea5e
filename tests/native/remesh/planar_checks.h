// Checks on planar triangle meshes shared by the optimization tests.
#pragma once

#include <algorithm>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace conformesh::testing {

//! The edges used by one triangle only (smaller vertex first).
inline std::set<std::pair<uint32_t, uint32_t>> boundaryEdges(const std::vector<uint32_t>& tri) {
  std::multiset<std::pair<uint32_t, uint32_t>> all;
  for (size_t t = 0; t < tri.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = tri[t + c], b = tri[t + (c + 1) % 3];
      all.insert({std::min(a, b), std::max(a, b)});
    }
  std::set<std::pair<uint32_t, uint32_t>> out;
  for (const auto& e : all)
    if (all.count(e) == 1) out.insert(e);
  return out;
}

}  // namespace conformesh::testing
