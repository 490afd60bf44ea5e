// Helpers shared by the mesh tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"
#include "mesh/primitives.h"

namespace conformesh::test {

struct NamedMesh {
  std::string name;
  MeshBuffers mesh;
  long chi;      // expected Euler characteristic (topology of the construction)
  long genus;
  size_t loops;  // boundary loops
};

// The generated surfaces with their known topology.
inline std::vector<NamedMesh> generatedMeshes() {
  return {
      {"icosahedron", makeIcosphere(0), 2, 0, 0},
      {"icosphere3", makeIcosphere(3), 2, 0, 0},
      {"torus", makeTorus(24, 12, 2.0, 0.5), 0, 1, 0},
      {"disk", makeDisk(5, 16, 1.0), 1, 0, 1},
      {"annulus", makeAnnulus(3, 20, 0.5, 1.5), 0, 0, 2},
      {"cube", makeCube(3, 1.0), 2, 0, 0},
      {"box-with-hole", makeBoxWithHole(3, 1.0, 0.4, 0.5), 0, 1, 0},
  };
}

// Same surface, triangles in random order, each triangle's corners rotated randomly, vertices
// renumbered randomly.
inline MeshBuffers shuffled(const MeshBuffers& m, uint32_t seed) {
  std::mt19937 rng(seed);
  const size_t nv = m.vertexCount(), nf = m.triangleCount();
  std::vector<uint32_t> perm(nv), order(nf);
  for (size_t i = 0; i < nv; ++i) perm[i] = uint32_t(i);
  for (size_t i = 0; i < nf; ++i) order[i] = uint32_t(i);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  MeshBuffers out;
  out.positions.resize(m.positions.size());
  for (size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) out.positions[3 * perm[v] + k] = m.positions[3 * v + k];
  for (uint32_t f : order) {
    int r = int(rng() % 3);
    for (int i = 0; i < 3; ++i) out.triangles.push_back(perm[m.triangles[3 * f + (i + r) % 3]]);
  }
  return out;
}

// Signed volume enclosed by a closed, consistently oriented mesh (positive: outward normals).
inline double signedVolume(const MeshBuffers& m) {
  double vol = 0;
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    const double* a = &m.positions[3 * m.triangles[3 * f]];
    const double* b = &m.positions[3 * m.triangles[3 * f + 1]];
    const double* c = &m.positions[3 * m.triangles[3 * f + 2]];
    vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return vol;
}

}  // namespace conformesh::test
