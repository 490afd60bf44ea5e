// conformesh — welding of coincident vertices: exact (hash on the bits) and within a tolerance
// (uniform grid with the 27 neighbour cells).
#include "mesh/weld_vertices.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
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

}  // namespace

namespace {

// Exact-position vertex table for triangle soups: positions are numbered in first-appearance
// order as they are inserted. Open addressing with linear probing, load <= 1/2, grows by doubling.
template <class T>
class SoupWelder {
 public:
  explicit SoupWelder(size_t expectedVertices) {
    slots_.assign(tableSize(expectedVertices), kEmpty);
    uniq_.reserve(3 * expectedVertices);
  }
  //! Vertex id of position p; callers pass -0 as +0 (equal values must hash equally).
  uint32_t insert(const T p[3]) {
    const size_t mask = slots_.size() - 1;
    size_t s = size_t(hash(p)) & mask;
    while (true) {
      const uint32_t id = slots_[s];
      if (id == kEmpty) break;
      const T* q = &uniq_[3 * size_t(id)];
      if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) return id;
      s = (s + 1) & mask;
    }
    const uint32_t id = uint32_t(uniq_.size() / 3);
    if (id >= io_detail::kMaxVertices) fail(Code::TooLarge, Stage::Read, "too many vertices");
    uniq_.insert(uniq_.end(), p, p + 3);
    slots_[s] = id;
    if (2 * (size_t(id) + 1) > slots_.size()) grow();
    return id;
  }
  void positionsTo(std::vector<double>& out) const { out.assign(uniq_.begin(), uniq_.end()); }

 private:
  static uint64_t hash(const T p[3]) {
    if constexpr (sizeof(T) == 4) {
      uint64_t a = uint64_t(floatBits(p[0])) | (uint64_t(floatBits(p[1])) << 32);
      return fmix64(a ^ (uint64_t(floatBits(p[2])) * 0x9E3779B97F4A7C15ull));
    } else {
      return fmix64(doubleBits(p[0]) ^ fmix64(doubleBits(p[1]) ^ fmix64(doubleBits(p[2]))));
    }
  }
  void grow() {
    std::vector<uint32_t> bigger(2 * slots_.size(), kEmpty);
    const size_t mask = bigger.size() - 1;
    const size_t n = uniq_.size() / 3;
    for (size_t id = 0; id < n; ++id) {
      size_t s = size_t(hash(&uniq_[3 * id])) & mask;
      while (bigger[s] != kEmpty) s = (s + 1) & mask;
      bigger[s] = uint32_t(id);
    }
    slots_.swap(bigger);
  }

  std::vector<uint32_t> slots_;
  std::vector<T> uniq_;
};

}  // namespace

namespace io_detail {

void weldSoupExact(const std::vector<double>& soup, MeshBuffers& mesh) {
  const size_t corners = soup.size() / 3;
  if (corners > kMaxVertices) fail(Code::TooLarge, Stage::Read, "too many triangle corners");
  SoupWelder<double> w(corners / 6 + 16);
  mesh.triangles.resize(corners);
  for (size_t c = 0; c < corners; ++c) {
    const double p[3] = {soup[3 * c] + 0.0, soup[3 * c + 1] + 0.0, soup[3 * c + 2] + 0.0};  // -0 -> +0
    mesh.triangles[c] = w.insert(p);
  }
  w.positionsTo(mesh.positions);
}

void weldBinaryStlRecords(const uint8_t* records, size_t triangles, MeshBuffers& mesh,
                          const std::function<void(size_t, int)>& nonFinite) {
  if (3 * uint64_t(triangles) > kMaxVertices) fail(Code::TooLarge, Stage::Read, "too many triangles");
  // A closed triangle mesh has about triangles / 2 vertices.
  SoupWelder<float> w(triangles / 2 + 16);
  mesh.triangles.resize(3 * triangles);
  const uint8_t* rec = records;
  for (size_t t = 0; t < triangles; ++t, rec += 50) {
    float v[9];
    std::memcpy(v, rec + 12, 36);  // little-endian float32 on every target we build for
    for (int k = 0; k < 9; ++k) {
      if (!std::isfinite(v[k])) nonFinite(t, k);
      v[k] += 0.0f;  // -0 -> +0
    }
    for (int c = 0; c < 3; ++c) mesh.triangles[3 * t + c] = w.insert(v + 3 * c);
  }
  w.positionsTo(mesh.positions);
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
    for (MeshAttribute& a : mesh.attributes)
      if (!a.perCorner) std::copy_n(&a.values[a.components * v], a.components, &a.values[a.components * kept]);
    ++kept;
  }
  mesh.positions.resize(3 * kept);
  if (hasUvs) mesh.uvs.resize(2 * kept);
  for (MeshAttribute& a : mesh.attributes)
    if (!a.perCorner) a.values.resize(a.components * kept);
  for (uint32_t& t : mesh.triangles) t = newIndex[rep[t]];
  return n - kept;
}

}  // namespace conformesh
