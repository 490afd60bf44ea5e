// Helpers for the mesh reader/writer tests: deterministic random polygon meshes, bytes, files.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::test {

//! SplitMix64 (Steele, Lea, Flood 2014): the same sequence on every platform.
struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed) {}
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
  uint32_t below(uint32_t n) { return uint32_t(next() % n); }
  //! A double with a random mantissa and exponent (not short in decimal).
  double coordinate() {
    double m = uniform() * 2.0 - 1.0;
    int e = int(below(21)) - 10;
    return m * std::ldexp(1.0, e);
  }
};

struct PolyMesh {
  std::vector<double> positions;             // 3 per vertex
  std::vector<double> uvs;                   // 2 per vertex
  std::vector<std::vector<uint32_t>> faces;  // polygons with 3..6 corners
};

//! Random polygon soup over nv distinct random vertices (every vertex used at least once).
inline PolyMesh randomPolyMesh(uint64_t seed, uint32_t nv = 40, uint32_t nf = 60) {
  Rng r(seed);
  PolyMesh m;
  for (uint32_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) m.positions.push_back(r.coordinate());
    for (int k = 0; k < 2; ++k) m.uvs.push_back(r.uniform());
  }
  uint32_t nextUnused = 0;
  for (uint32_t f = 0; f < nf || nextUnused < nv; ++f) {
    uint32_t k = 3 + r.below(4);
    std::vector<uint32_t> face;
    for (uint32_t i = 0; i < k; ++i) face.push_back(nextUnused < nv ? nextUnused++ : r.below(nv));
    m.faces.push_back(face);
  }
  return m;
}

//! The fan triangulation (0, i, i+1) the readers produce.
inline std::vector<uint32_t> fanTriangles(const PolyMesh& m) {
  std::vector<uint32_t> t;
  for (const auto& f : m.faces)
    for (size_t i = 1; i + 1 < f.size(); ++i) t.insert(t.end(), {f[0], f[i], f[i + 1]});
  return t;
}

//! Triangle-mesh version of a PolyMesh (for writers).
inline MeshBuffers toBuffers(const PolyMesh& m, bool withUvs) {
  MeshBuffers b;
  b.positions = m.positions;
  b.triangles = fanTriangles(m);
  if (withUvs) b.uvs = m.uvs;
  return b;
}

inline std::vector<uint8_t> bytesOf(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

//! "%.17g": exact text for a double.
inline std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace conformesh::test
