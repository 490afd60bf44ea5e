// conformesh — welding of coincident vertices: exact (hash on the bits) and within a tolerance
// (uniform grid with the 27 neighbour cells).
#include "mesh/weld_vertices.h"

#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/io_detail.h"

namespace conformesh {

namespace {

constexpr uint32_t kEmpty = 0xFFFFFFFFu;

uint64_t fmix64(uint64_t k) {  // MurmurHash3 finalizer (Appleby): a good 64-bit bit mixer
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return k;
}

uint64_t doubleBits(double v) {
  if (v == 0.0) v = 0.0;  // -0 and +0 are equal positions
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

uint32_t floatBits(float v) {
  if (v == 0.0f) v = 0.0f;
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

size_t tableSize(size_t n) {
  size_t cap = 16;
  while (cap < 2 * n) cap <<= 1;
  return cap;
}

// Open-addressing table of indices into an external key array. `hashOf(i)` and `same(i, j)` say
// how to hash and compare the keys of items i, j. Returns for every item the first item with an
// equal key, items being visited in order.
template <class HashOf, class Same>
std::vector<uint32_t> firstEqual(size_t n, HashOf hashOf, Same same) {
  std::vector<uint32_t> slots(tableSize(n), kEmpty);
  const size_t mask = slots.size() - 1;
  std::vector<uint32_t> first(n);
  for (size_t i = 0; i < n; ++i) {
    size_t s = size_t(hashOf(i)) & mask;
    while (true) {
      uint32_t j = slots[s];
      if (j == kEmpty) {
        slots[s] = uint32_t(i);
        first[i] = uint32_t(i);
        break;
      }
      if (same(j, i)) {
        first[i] = j;
        break;
      }
      s = (s + 1) & mask;
    }
  }
  return first;
}

// From "first equal item" per corner: vertices numbered by first appearance.
template <class Emit>
void numberByFirstAppearance(const std::vector<uint32_t>& first, std::vector<uint32_t>& triangles,
                             Emit emitVertex) {
  const size_t n = first.size();
  triangles.resize(n);
  std::vector<uint32_t> vertexOf(n, kEmpty);
  uint32_t next = 0;
  for (size_t i = 0; i < n; ++i) {
    uint32_t f = first[i];
    if (vertexOf[f] == kEmpty) {
      vertexOf[f] = next++;
      emitVertex(f);
    }
    triangles[i] = vertexOf[f];
  }
}

}  // namespace

namespace io_detail {

void weldSoupExact(const std::vector<double>& soup, MeshBuffers& mesh) {
  const size_t n = soup.size() / 3;
  if (n > kMaxVertices) fail(Code::TooLarge, Stage::Read, "too many triangle corners");
  const double* s = soup.data();
  auto hashOf = [s](size_t i) {
    const double* p = s + 3 * i;
    return fmix64(doubleBits(p[0]) ^ fmix64(doubleBits(p[1]) ^ fmix64(doubleBits(p[2]))));
  };
  auto same = [s](size_t a, size_t b) {
    const double* p = s + 3 * a;
    const double* q = s + 3 * b;
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  };
  std::vector<uint32_t> first = firstEqual(n, hashOf, same);
  mesh.positions.clear();
  numberByFirstAppearance(first, mesh.triangles, [&](uint32_t f) {
    const double* p = s + 3 * size_t(f);
    mesh.positions.insert(mesh.positions.end(), p, p + 3);
  });
}

void weldSoupExactFloat(const std::vector<float>& soup, MeshBuffers& mesh) {
  const size_t n = soup.size() / 3;
  if (n > kMaxVertices) fail(Code::TooLarge, Stage::Read, "too many triangle corners");
  const float* s = soup.data();
  auto hashOf = [s](size_t i) {
    const float* p = s + 3 * i;
    uint64_t a = uint64_t(floatBits(p[0])) | (uint64_t(floatBits(p[1])) << 32);
    return fmix64(a ^ (uint64_t(floatBits(p[2])) * 0x9E3779B97F4A7C15ull));
  };
  auto same = [s](size_t a, size_t b) {
    const float* p = s + 3 * a;
    const float* q = s + 3 * b;
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  };
  std::vector<uint32_t> first = firstEqual(n, hashOf, same);
  mesh.positions.clear();
  mesh.positions.reserve(n);  // typical closed meshes: about n / 6 vertices; grows if needed
  numberByFirstAppearance(first, mesh.triangles, [&](uint32_t f) {
    const float* p = s + 3 * size_t(f);
    mesh.positions.push_back(double(p[0]));
    mesh.positions.push_back(double(p[1]));
    mesh.positions.push_back(double(p[2]));
  });
}

}  // namespace io_detail

namespace {

struct Cell {
  int64_t x, y, z;
  bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  size_t operator()(const Cell& c) const {
    return size_t(fmix64(uint64_t(c.x) ^ fmix64(uint64_t(c.y) ^ fmix64(uint64_t(c.z)))));
  }
};

// For every vertex, the vertex it merges into (itself when kept).
std::vector<uint32_t> representativesWithin(const std::vector<double>& pos, double tol, Stage stage) {
  const size_t n = pos.size() / 3;
  const double inv = 1.0 / tol;
  const double limit = std::ldexp(1.0, 50);
  auto cellOf = [&](size_t v) {
    double c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = std::floor(pos[3 * v + k] * inv);
      if (!(std::fabs(c[k]) < limit))
        fail(Code::InvalidArgument, stage,
             "weld tolerance " + std::to_string(tol) + " is too small for the coordinate range");
    }
    return Cell{int64_t(c[0]), int64_t(c[1]), int64_t(c[2])};
  };
  std::unordered_map<Cell, std::vector<uint32_t>, CellHash> grid;
  grid.reserve(n);
  std::vector<uint32_t> rep(n);
  const double tol2 = tol * tol;
  for (size_t v = 0; v < n; ++v) {
    const Cell c = cellOf(v);
    uint32_t best = kEmpty;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(Cell{c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (uint32_t r : it->second) {
            if (r >= best) continue;
            double d2 = 0;
            for (int k = 0; k < 3; ++k) {
              double d = pos[3 * v + k] - pos[3 * size_t(r) + k];
              d2 += d * d;
            }
            if (d2 <= tol2) best = r;
          }
        }
    if (best == kEmpty) {
      rep[v] = uint32_t(v);
      grid[c].push_back(uint32_t(v));
    } else {
      rep[v] = best;
    }
  }
  return rep;
}

}  // namespace

size_t weldVertices(MeshBuffers& mesh, double tolerance, Stage stage) {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    fail(Code::InvalidArgument, stage, "weld tolerance must be a finite number >= 0");
  const size_t n = mesh.vertexCount();
  if (n > io_detail::kMaxVertices) fail(Code::TooLarge, stage, "too many vertices to weld");
  for (size_t i = 0; i < 3 * n; ++i)
    if (!std::isfinite(mesh.positions[i]))
      fail(Code::NonFiniteCoordinate, stage, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
  for (uint32_t t : mesh.triangles)
    if (t >= n) fail(Code::IndexOutOfRange, stage, "triangle index " + std::to_string(t) + " >= vertex count");

  std::vector<uint32_t> rep;
  if (tolerance == 0.0) {
    const double* s = mesh.positions.data();
    rep = firstEqual(
        n,
        [s](size_t i) {
          const double* p = s + 3 * i;
          return fmix64(doubleBits(p[0]) ^ fmix64(doubleBits(p[1]) ^ fmix64(doubleBits(p[2]))));
        },
        [s](size_t a, size_t b) {
          const double* p = s + 3 * a;
          const double* q = s + 3 * b;
          return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
        });
  } else {
    rep = representativesWithin(mesh.positions, tolerance, stage);
  }

  const bool hasUvs = mesh.uvs.size() == 2 * n;
  std::vector<uint32_t> newIndex(n, kEmpty);
  size_t kept = 0;
  for (size_t v = 0; v < n; ++v) {
    if (rep[v] != v) continue;
    newIndex[v] = uint32_t(kept);
    for (int k = 0; k < 3; ++k) mesh.positions[3 * kept + k] = mesh.positions[3 * v + k];
    if (hasUvs)
      for (int k = 0; k < 2; ++k) mesh.uvs[2 * kept + k] = mesh.uvs[2 * v + k];
    ++kept;
  }
  mesh.positions.resize(3 * kept);
  if (hasUvs) mesh.uvs.resize(2 * kept);
  for (uint32_t& t : mesh.triangles) t = newIndex[rep[t]];
  return n - kept;
}

}  // namespace conformesh
