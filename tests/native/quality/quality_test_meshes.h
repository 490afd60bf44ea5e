// Small meshes shared by the quality tests.
#pragma once

#include <cstdint>

#include "core/mesh_buffers.h"

namespace conformesh::quality_test {

//! An n×n grid of squares on [0,1]², each split along a diagonal, lifted by z = f(x, y).
template <class F>
MeshBuffers grid(int n, F height) {
  MeshBuffers m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      double x = double(i) / n, y = double(j) / n;
      m.positions.insert(m.positions.end(), {x, y, height(x, y)});
    }
  auto id = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace conformesh::quality_test
