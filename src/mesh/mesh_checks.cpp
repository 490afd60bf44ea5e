#include "mesh/mesh_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/bucket_sort.h"
#include "mesh/edge_groups.h"
#include "mesh/mesh_geometry.h"

namespace conformesh::detail {

UnionFind::UnionFind(size_t n) : parent(n) {
  for (size_t i = 0; i < n; ++i) parent[i] = uint32_t(i);
}

uint32_t UnionFind::find(uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

bool UnionFind::unite(uint32_t a, uint32_t b) {
  a = find(a);
  b = find(b);
  if (a == b) return false;
  if (a < b) std::swap(a, b);
  parent[a] = b;  // the smaller index stays the root: deterministic representatives
  return true;
}

void checkBuffers(const MeshBuffers& m, size_t maxVertices, size_t maxTriangles, Stage stage) {
  if (m.positions.size() % 3 != 0)
    fail(Code::InvalidArgument, stage, "positions has " + std::to_string(m.positions.size()) +
                                           " values, not a multiple of 3");
  if (m.triangles.size() % 3 != 0)
    fail(Code::InvalidArgument, stage, "triangles has " + std::to_string(m.triangles.size()) +
                                           " indices, not a multiple of 3");
  const size_t nv = m.vertexCount(), nf = m.triangleCount();
  if (!m.uvs.empty() && m.uvs.size() != 2 * nv)
    fail(Code::InvalidArgument, stage, "uvs has " + std::to_string(m.uvs.size()) + " values, expected 0 or " +
                                           std::to_string(2 * nv));
  if (nv == 0 || nf == 0)
    fail(Code::EmptyMesh, stage, "the mesh has " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                     " triangles");
  // Hard limits of the 32-bit handles (6 halfedges per triangle) whatever the options say.
  const size_t hardV = 0xfffffffeu, hardF = 0x7fffffffu / 6;
  if (nv > std::min(maxVertices, hardV))
    fail(Code::TooLarge, stage, std::to_string(nv) + " vertices exceed the limit of " +
                                    std::to_string(std::min(maxVertices, hardV)));
  if (nf > std::min(maxTriangles, hardF))
    fail(Code::TooLarge, stage, std::to_string(nf) + " triangles exceed the limit of " +
                                    std::to_string(std::min(maxTriangles, hardF)));
  for (size_t i = 0; i < m.triangles.size(); ++i)
    if (m.triangles[i] >= nv)
      fail(Code::IndexOutOfRange, stage, "triangle " + std::to_string(i / 3) + " refers to vertex " +
                                             std::to_string(m.triangles[i]) + " but there are only " +
                                             std::to_string(nv) + " vertices");
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!std::isfinite(m.positions[i]))
      fail(Code::NonFiniteCoordinate, stage, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate (" +
                                                 std::string(std::isnan(m.positions[i]) ? "NaN" : "infinite") + ")");
  for (size_t i = 0; i < m.uvs.size(); ++i)
    if (!std::isfinite(m.uvs[i]))
      fail(Code::NonFiniteCoordinate, stage, "vertex " + std::to_string(i / 2) + " has a non-finite uv");
}

FaceFilter filterDegenerateFaces(const MeshBuffers& m, bool dropZeroArea) {
  FaceFilter out;
  const size_t nf = m.triangleCount();
  out.tris.reserve(3 * nf);
  out.faceToInput.reserve(nf);
  const double* p = m.positions.data();
  for (size_t f = 0; f < nf; ++f) {
    uint32_t a = m.triangles[3 * f], b = m.triangles[3 * f + 1], c = m.triangles[3 * f + 2];
    bool degenerate = false;
    if (a == b || b == c || a == c) {
      ++out.repeatedVertex;
      degenerate = true;
    } else if (exactlyCollinear(p + 3 * size_t(a), p + 3 * size_t(b), p + 3 * size_t(c))) {
      ++out.zeroArea;
      degenerate = dropZeroArea;
      if (out.firstDegenerate == kNone) out.firstDegenerate = uint32_t(f);
    }
    if (degenerate) {
      if (out.firstDegenerate == kNone) out.firstDegenerate = uint32_t(f);
      continue;
    }
    out.tris.insert(out.tris.end(), {a, b, c});
    out.faceToInput.push_back(uint32_t(f));
  }
  return out;
}

Duplicates findDuplicateFaces(const std::vector<uint32_t>& tris) {
  const size_t nf = tris.size() / 3;
  std::vector<std::array<uint32_t, 4>> keys(nf);
  for (size_t f = 0; f < nf; ++f) {
    std::array<uint32_t, 3> v = {tris[3 * f], tris[3 * f + 1], tris[3 * f + 2]};
    std::sort(v.begin(), v.end());
    keys[f] = {v[0], v[1], v[2], uint32_t(f)};
  }
  uint32_t maxLo = 0;
  for (const auto& k : keys) maxLo = std::max(maxLo, k[0]);
  bucketSort(keys, size_t(maxLo) + 1, [](const std::array<uint32_t, 4>& k) { return k[0]; },
             [](const std::array<uint32_t, 4>& x, const std::array<uint32_t, 4>& y) { return x < y; });
  Duplicates d;
  d.isDuplicate.assign(nf, 0);
  for (size_t i = 1; i < nf; ++i) {
    const auto& k = keys[i];
    const auto& prev = keys[i - 1];
    if (k[0] == prev[0] && k[1] == prev[1] && k[2] == prev[2]) {
      d.isDuplicate[k[3]] = 1;  // keys sorted by face within equal triples: prev is earlier
      ++d.count;
      if (d.first == kNone || k[3] < d.first) {
        d.first = k[3];
        size_t j = i - 1;
        while (j > 0 && keys[j - 1][0] == k[0] && keys[j - 1][1] == k[1] && keys[j - 1][2] == k[2]) --j;
        d.firstOriginal = keys[j][3];
      }
    }
  }
  return d;
}

EdgeStats edgeStats(const EdgeGroups& g, const std::vector<uint32_t>& tris) {
  EdgeStats s;
  s.edges = g.groupCount();
  s.partner.assign(tris.size(), kNone);
  for (size_t e = 0; e < s.edges; ++e) {
    const uint32_t* c = g.corners.data() + g.groupStart[e];
    const uint32_t n = g.groupSize(e);
    if (n == 1) {
      ++s.boundaryEdges;
      s.boundaryCorners.push_back(c[0]);
    } else if (n == 2) {
      s.partner[c[0]] = c[1];
      s.partner[c[1]] = c[0];
    } else {
      ++s.nonManifoldEdges;
      if (s.firstNonManifoldCorner == kNone) {
        s.firstNonManifoldCorner = c[0];
        s.firstNonManifoldFaces = n;
      }
    }
  }
  return s;
}

Orientation orientFaces(const std::vector<uint32_t>& tris, const std::vector<uint32_t>& partner) {
  const uint32_t nf = uint32_t(tris.size() / 3);
  Orientation o;
  o.flip.assign(nf, 0);
  std::vector<uint8_t> seen(nf, 0);
  std::vector<uint32_t> queue;
  queue.reserve(nf);
  for (uint32_t c = 0; c < tris.size(); ++c)
    if (partner[c] != kNone && c < partner[c] && tris[c] == tris[partner[c]]) ++o.inconsistentEdges;
  for (uint32_t seed = 0; seed < nf; ++seed) {
    if (seen[seed]) continue;
    queue.clear();
    queue.push_back(seed);
    seen[seed] = 1;
    bool orientable = true;
    for (size_t qi = 0; qi < queue.size(); ++qi) {
      uint32_t f = queue[qi];
      for (uint32_t i = 0; i < 3; ++i) {
        uint32_t c = 3 * f + i, d = partner[c];
        if (d == kNone) continue;
        uint32_t g = d / 3;
        // Same tail vertex on the shared edge: same traversal direction, so opposite orientation.
        uint8_t want = uint8_t(o.flip[f] ^ (tris[c] == tris[d] ? 1 : 0));
        if (!seen[g]) {
          seen[g] = 1;
          o.flip[g] = want;
          queue.push_back(g);
        } else if (o.flip[g] != want) {
          orientable = false;
        }
      }
    }
    if (!orientable) {
      ++o.nonOrientableComponents;
      if (o.firstNonOrientableFace == kNone) o.firstNonOrientableFace = seed;
      for (uint32_t f : queue) o.flip[f] = 0;
      continue;
    }
    size_t flips = 0;
    for (uint32_t f : queue) flips += o.flip[f];
    if (2 * flips > queue.size()) {
      for (uint32_t f : queue) o.flip[f] ^= 1;
      flips = queue.size() - flips;
    }
    o.flipped += flips;
  }
  return o;
}

Fans vertexFans(size_t vertexCount, const std::vector<uint32_t>& tris, const std::vector<uint32_t>& partner) {
  const uint32_t nc = uint32_t(tris.size());
  UnionFind uf(nc);
  auto nextCorner = [](uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; };
  for (uint32_t c = 0; c < nc; ++c) {
    uint32_t d = partner[c];
    if (d == kNone || d < c) continue;
    if (tris[c] == tris[d]) {  // same direction
      uf.unite(c, d);
      uf.unite(nextCorner(c), nextCorner(d));
    } else {  // opposite: c's tail is d's tip
      uf.unite(c, nextCorner(d));
      uf.unite(nextCorner(c), d);
    }
  }
  Fans fans;
  fans.cornerFan.resize(nc);
  std::vector<uint32_t> fanCount(vertexCount, 0);
  for (uint32_t c = 0; c < nc; ++c) {
    uint32_t r = uf.find(c);
    fans.cornerFan[c] = r;
    if (r == c) ++fanCount[tris[c]];
  }
  for (size_t v = 0; v < vertexCount; ++v) {
    if (fanCount[v] > 1) {
      ++fans.bowtieVertices;
      fans.extraFans += fanCount[v] - 1;
      if (fans.firstBowtie == kNone) fans.firstBowtie = uint32_t(v);
    }
  }
  return fans;
}

}  // namespace conformesh::detail
