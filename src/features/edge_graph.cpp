#include "features/edge_graph.h"

#include <algorithm>
#include <string>

namespace conformesh::features {

Vec3 EdgeGraph::faceNormal(uint32_t f) const {
  const auto& t = faces[f];
  Vec3 n = cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
  double l = norm(n);
  return l > 0 ? n * (1.0 / l) : Vec3{};
}

double EdgeGraph::faceArea(uint32_t f) const {
  const auto& t = faces[f];
  return 0.5 * norm(cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]));
}

Vec3 EdgeGraph::faceCentroid(uint32_t f) const {
  const auto& t = faces[f];
  return (positions[t[0]] + positions[t[1]] + positions[t[2]]) * (1.0 / 3.0);
}

double EdgeGraph::cornerAngle(uint32_t f, int i) const {
  const auto& t = faces[f];
  const Vec3& p = positions[t[i]];
  return angleBetween(positions[t[(i + 1) % 3]] - p, positions[t[(i + 2) % 3]] - p);
}

uint32_t EdgeGraph::findEdge(uint32_t a, uint32_t b) const {
  for (uint32_t k = vertexEdgeStart[a]; k < vertexEdgeStart[a + 1]; ++k) {
    uint32_t e = vertexEdgeIds[k];
    if (otherVertex(e, a) == b) return e;
  }
  return kNone;
}

EdgeGraph buildEdgeGraph(const MeshBuffers& mesh) {
  EdgeGraph g;
  if (mesh.positions.empty() || mesh.triangles.empty())
    fail(Code::EmptyMesh, Stage::Segment, "the mesh has no vertices or no triangles");
  g.vertexCount = uint32_t(mesh.vertexCount());
  g.faceCount = uint32_t(mesh.triangleCount());
  g.positions.resize(g.vertexCount);
  for (uint32_t v = 0; v < g.vertexCount; ++v)
    g.positions[v] = vec3At(mesh.positions, v);
  g.faces.resize(g.faceCount);
  struct HalfKey {
    uint64_t key;
    uint32_t face;
    uint8_t corner;
  };
  for (uint32_t f = 0; f < g.faceCount; ++f)
    for (int i = 0; i < 3; ++i) {
      uint32_t v = mesh.triangles[3 * size_t(f) + i];
      if (v >= g.vertexCount)
        fail(Code::IndexOutOfRange, Stage::Segment,
             "triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v));
      g.faces[f][i] = v;
    }
  // every face side as a half, ordered by (key, face)
  std::vector<HalfKey> halves;
  auto forEachHalf = [&](auto&& visit) {
    for (uint32_t f = 0; f < g.faceCount; ++f)
      for (int i = 0; i < 3; ++i) {
        uint32_t a = g.faces[f][i], b = g.faces[f][(i + 1) % 3];
        uint64_t lo = std::min(a, b), hi = std::max(a, b);
        visit(HalfKey{(lo << 32) | hi, f, uint8_t(i)});
      }
  };
  auto byKeyFace = [](const HalfKey& a, const HalfKey& b) { return a.key != b.key ? a.key < b.key : a.face < b.face; };
  bool repeated = false;
  for (const auto& t : g.faces) repeated = repeated || t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
  if (repeated) {
    halves.reserve(3 * size_t(g.faceCount));
    forEachHalf([&](const HalfKey& h) { halves.push_back(h); });
    std::sort(halves.begin(), halves.end(), byKeyFace);
  } else {
    // No two halves share (key, face), so the order is unique: a counting sort on the smaller
    // vertex (faces ascending within a bucket, as visited), then each bucket, about the vertex's
    // degree of entries, sorted on the key.
    std::vector<uint32_t> start(size_t(g.vertexCount) + 1, 0);
    forEachHalf([&](const HalfKey& h) { ++start[(h.key >> 32) + 1]; });
    for (uint32_t v = 0; v < g.vertexCount; ++v) start[v + 1] += start[v];
    halves.resize(3 * size_t(g.faceCount));
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    forEachHalf([&](const HalfKey& h) { halves[fill[h.key >> 32]++] = h; });
    for (uint32_t v = 0; v < g.vertexCount; ++v) {
      HalfKey* lo = halves.data() + start[v];
      HalfKey* hi = halves.data() + start[v + 1];
      if (hi - lo > 24) {
        std::sort(lo, hi, byKeyFace);
        continue;
      }
      for (HalfKey* i = lo + 1; i < hi; ++i)
        for (HalfKey* j = i; j > lo && byKeyFace(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
    }
  }
  // about one edge per two halves (more with boundary edges)
  g.edgeVerts.reserve(halves.size() / 2 + halves.size() / 16 + 1);
  g.edgeFaces.reserve(halves.size() / 2 + halves.size() / 16 + 1);
  g.faceEdges.assign(g.faceCount, {kNone, kNone, kNone});
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].key == halves[i].key) ++j;
    if (j - i > 2)
      fail(Code::NonManifoldEdge, Stage::Segment,
           "edge (" + std::to_string(halves[i].key >> 32) + ", " +
               std::to_string(halves[i].key & 0xffffffffu) + ") has " + std::to_string(j - i) + " faces");
    uint32_t e = uint32_t(g.edgeVerts.size());
    uint32_t lo = uint32_t(halves[i].key >> 32), hi = uint32_t(halves[i].key & 0xffffffffu);
    g.edgeVerts.push_back({lo, hi});
    std::array<uint32_t, 2> fs{kNone, kNone};
    for (size_t k = i; k < j; ++k) {
      uint32_t f = halves[k].face;
      int c = halves[k].corner;
      g.faceEdges[f][c] = e;
      bool forward = g.faces[f][c] == lo;
      // put the face traversing lo -> hi first when possible
      if (forward && fs[0] == kNone) fs[0] = f;
      else if (fs[1] == kNone) fs[1] = f;
      else fs[0] = f;
    }
    if (fs[0] == kNone) std::swap(fs[0], fs[1]);
    g.edgeFaces.push_back(fs);
    i = j;
  }
  g.vertexEdgeStart.assign(g.vertexCount + 1, 0);
  for (const auto& ev : g.edgeVerts) {
    ++g.vertexEdgeStart[ev[0] + 1];
    ++g.vertexEdgeStart[ev[1] + 1];
  }
  for (uint32_t v = 0; v < g.vertexCount; ++v) g.vertexEdgeStart[v + 1] += g.vertexEdgeStart[v];
  g.vertexEdgeIds.resize(g.vertexEdgeStart.back());
  std::vector<uint32_t> fill(g.vertexEdgeStart.begin(), g.vertexEdgeStart.end() - 1);
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    g.vertexEdgeIds[fill[g.edgeVerts[e][0]]++] = e;
    g.vertexEdgeIds[fill[g.edgeVerts[e][1]]++] = e;
  }
  return g;
}

}  // namespace conformesh::features
