// conformesh — grouping a triangle list's corners by undirected edge (internal to src/mesh).
//
// Corner c = 3f + i of a triangle list stands for the directed edge from triangles[c] to
// triangles[3f + (i+1)%3]. groupEdges() puts the corners of each undirected edge next to each
// other, in O(nF log d) time (counting sort by the smaller vertex, then a sort of each bucket by
// the larger one; d = largest vertex degree). The order is deterministic: by smaller vertex, then
// larger vertex, then corner.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace conformesh::detail {

struct EdgeGroups {
  std::vector<uint32_t> corners;     //!< all 3·nF corners, grouped
  std::vector<uint32_t> groupStart;  //!< group g is corners[groupStart[g] .. groupStart[g+1])

  size_t groupCount() const { return groupStart.empty() ? 0 : groupStart.size() - 1; }
  uint32_t groupSize(size_t g) const { return groupStart[g + 1] - groupStart[g]; }
};

//! Corner c's end vertex (the tail of the next corner in its triangle).
inline uint32_t cornerTip(const std::vector<uint32_t>& tris, uint32_t c) {
  uint32_t f = c / 3, i = c % 3;
  return tris[3 * f + (i == 2 ? 0 : i + 1)];
}

//! Group corners by undirected edge. Pre: every index < vertexCount, tris.size() % 3 == 0,
//! tris.size() < 2^32.
EdgeGroups groupEdges(size_t vertexCount, const std::vector<uint32_t>& tris);

}  // namespace conformesh::detail
