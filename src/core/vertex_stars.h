// conformesh — the triangles around each vertex of a triangle list, as one CSR array.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace conformesh {

//! The triangles of vertex v are items[start[v] .. start[v + 1]), in increasing order. tris: three
//! vertex indices per triangle, each < vertexCount. The vectors are reused (assigned, not appended).
inline void vertexStars(const std::vector<uint32_t>& tris, size_t vertexCount, std::vector<uint32_t>& start,
                        std::vector<uint32_t>& items) {
  start.assign(vertexCount + 1, 0);
  for (uint32_t v : tris) ++start[v + 1];
  for (size_t i = 0; i < vertexCount; ++i) start[i + 1] += start[i];
  items.assign(tris.size(), 0);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < tris.size() / 3; ++t)
    for (int c = 0; c < 3; ++c) items[fill[tris[3 * t + c]]++] = uint32_t(t);
}

}  // namespace conformesh
