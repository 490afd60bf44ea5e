#include "mesh/edge_groups.h"

#include <algorithm>

namespace conformesh::detail {

EdgeGroups groupEdges(size_t vertexCount, const std::vector<uint32_t>& tris) {
  const uint32_t nc = uint32_t(tris.size());
  // Counting sort of the corners by their smaller vertex.
  std::vector<uint32_t> start(vertexCount + 1, 0);
  for (uint32_t c = 0; c < nc; ++c) {
    uint32_t a = tris[c], b = cornerTip(tris, c);
    ++start[std::min(a, b) + 1];
  }
  for (size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
  // key = larger vertex << 32 | corner: sorting a bucket by key groups equal edges, corners in order.
  std::vector<uint64_t> keys(nc);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t c = 0; c < nc; ++c) {
      uint32_t a = tris[c], b = cornerTip(tris, c);
      uint32_t lo = std::min(a, b), hi = std::max(a, b);
      keys[fill[lo]++] = (uint64_t(hi) << 32) | c;
    }
  }
  EdgeGroups g;
  g.corners.resize(nc);
  g.groupStart.reserve(nc / 2 + 2);
  for (size_t v = 0; v < vertexCount; ++v) {
    uint64_t* b = keys.data() + start[v];
    uint64_t* e = keys.data() + start[v + 1];
    if (e - b > 1) {
      if (e - b <= 16) {  // insertion sort: typical buckets hold about 3 corners
        for (uint64_t* p = b + 1; p < e; ++p) {
          uint64_t k = *p;
          uint64_t* q = p;
          while (q > b && *(q - 1) > k) {
            *q = *(q - 1);
            --q;
          }
          *q = k;
        }
      } else {
        std::sort(b, e);
      }
    }
    for (uint64_t* p = b; p < e; ++p) {
      size_t i = size_t(p - keys.data());
      if (p == b || (*p >> 32) != (*(p - 1) >> 32)) g.groupStart.push_back(uint32_t(i));
      g.corners[i] = uint32_t(*p);
    }
  }
  g.groupStart.push_back(nc);
  return g;
}

}  // namespace conformesh::detail
