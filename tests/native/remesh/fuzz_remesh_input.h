// Decoding of fuzzer bytes into a small mesh and remesh options. Shared by the libFuzzer harness
// (tests/fuzz/fuzz_remesh.cpp) and the doctest that replays its findings
// (tests/native/remesh/fuzz_regressions_test.cpp), so a finding replays exactly.
//
// Byte 0: options (min angle 20/25/30/34, feature angle 20/40/60/90 degrees, target edge length
//         0.15/0.25/0.35/0.5 of the diagonal). Byte 1: the kind of mesh:
//   even: a height field over an nx × ny grid (1..4 each; bytes 2-3), heights from the next
//         bytes in {-2 .. 2} / 4, x/y jitter in quarter cells from the bytes after, and a bit mask
//         of dropped triangles (holes, several components, bow-ties),
//   odd:  3..8 vertices on a 4 × 4 × 4 integer grid and up to 12 triangles of any three of them
//         (mostly invalid: the validation statuses get fuzzed too).
// Missing bytes read as 0. Every execution is small: maxTriangles 3000, no Hausdorff.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "remesh/remesh.h"

namespace conformesh::fuzz {

struct RemeshInput {
  MeshBuffers mesh;
  RemeshOptions options;
};

inline RemeshInput decodeRemeshInput(const uint8_t* data, size_t size) {
  size_t at = 0;
  auto next = [&]() -> uint32_t { return at < size ? data[at++] : 0u; };
  RemeshInput in;
  RemeshOptions& o = in.options;
  const uint32_t ob = next();
  const double angles[4] = {20, 25, 30, 34}, features[4] = {20, 40, 60, 90}, sizes[4] = {0.15, 0.25, 0.35, 0.5};
  o.minAngle = angles[ob & 3];
  o.featureAngle = features[(ob >> 2) & 3];
  o.targetEdgeLengthRel = sizes[(ob >> 4) & 3];
  o.computeHausdorff = false;
  o.maxTriangles = 3000;
  o.maxVertices = 2000;
  o.maxCertificateRounds = 2;
  MeshBuffers& m = in.mesh;
  if ((next() & 1) == 0) {
    const int nx = 1 + int(next() % 4), ny = 1 + int(next() % 4);
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        double z = (int(next() % 5) - 2) / 4.0;
        uint32_t jit = next();
        double dx = (int(jit & 3) - 1.5) / 8.0, dy = (int((jit >> 2) & 3) - 1.5) / 8.0;
        if (i == 0 || i == nx) dx = 0;  // keep the outline a rectangle: jitter only inside
        if (j == 0 || j == ny) dy = 0;
        m.positions.insert(m.positions.end(), {i + dx, j + dy, z});
      }
    auto id = [&](int i, int j) { return uint32_t(j * (nx + 1) + i); };
    uint32_t drop = next() | (next() << 8) | (next() << 16) | (next() << 24);
    int k = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool diag = (next() & 1) != 0;  // which diagonal splits the quad
        uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
        uint32_t t[6] = {a, b, c, a, c, d};
        if (diag) t[0] = a, t[1] = b, t[2] = d, t[3] = b, t[4] = c, t[5] = d;
        for (int h = 0; h < 2; ++h, ++k)
          if (!((drop >> (k % 32)) & 1) || drop == 0xffffffffu)
            m.triangles.insert(m.triangles.end(), {t[3 * h], t[3 * h + 1], t[3 * h + 2]});
      }
  } else {
    const uint32_t nv = 3 + next() % 6;
    for (uint32_t v = 0; v < nv; ++v) {
      uint32_t c = next();
      m.positions.insert(m.positions.end(), {double(c & 3), double((c >> 2) & 3), double((c >> 4) & 3)});
    }
    const uint32_t nt = 1 + next() % 12;
    for (uint32_t t = 0; t < nt; ++t)
      m.triangles.insert(m.triangles.end(), {next() % nv, next() % nv, next() % nv});
  }
  return in;
}

}  // namespace conformesh::fuzz
