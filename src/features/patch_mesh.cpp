#include <algorithm>
#include "features/patch_mesh.h"
#include "core/union_find.h"

namespace conformesh::features {

namespace {

// Per input face (or vertex) of the graph, a slot that is kNone except while a call uses it:
// each call sets the entries it needs and puts them back, so it costs O(patch), not O(mesh),
// however many patches are extracted (one per thread: extractions run on the patch threads).
struct Slots {
  std::vector<uint32_t> at;
  std::vector<uint32_t> used;
  void reserve(size_t n) {
    if (at.size() < n) at.resize(n, kNone);
  }
  void set(uint32_t i, uint32_t value) {
    if (at[i] == kNone) used.push_back(i);
    at[i] = value;
  }
  void clear() {
    for (uint32_t i : used) at[i] = kNone;
    used.clear();
  }
};

}  // namespace

PatchMesh extractPatch(const EdgeGraph& g, const std::vector<uint8_t>& isCurve,
                       const std::vector<uint32_t>& faces, bool traceLoops) {
  PatchMesh pm;
  const uint32_t nF = uint32_t(faces.size());
  thread_local Slots local;  // input face -> its index in `faces`
  local.reserve(g.faceCount);
  struct Clear {
    Slots& s;
    ~Clear() { s.clear(); }
  } clearLocal{local};  // also when a check below throws
  for (uint32_t i = 0; i < nF; ++i) local.set(faces[i], i);
  auto localOf = [&](uint32_t f) { return local.at[f]; };
  // corners (i, c) -> 3i + c; unite corners of the same input vertex across non-curve edges
  UnionFind uf(3 * size_t(nF));
  uint32_t boundaryHalfedges = 0;
  std::vector<uint8_t> heBoundary(3 * size_t(nF), 0);
  for (uint32_t i = 0; i < nF; ++i) {
    uint32_t f = faces[i];
    for (int c = 0; c < 3; ++c) {
      uint32_t e = g.faceEdges[f][c];
      uint32_t other = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
      uint32_t j = other == kNone ? kNone : localOf(other);
      if (isCurve[e] || j == kNone) {
        heBoundary[3 * i + c] = 1;
        ++boundaryHalfedges;
        continue;
      }
      if (j < i) continue;
      uint32_t a = g.faces[f][c], b = g.faces[f][(c + 1) % 3];
      for (int d = 0; d < 3; ++d) {
        if (g.faces[other][d] == a) uf.unite(3 * i + c, 3 * j + d);
        if (g.faces[other][d] == b) uf.unite(3 * i + (c + 1) % 3, 3 * j + d);
      }
    }
  }
  std::vector<uint32_t> rootVertex(3 * size_t(nF), kNone);
  pm.mesh.triangles.resize(3 * size_t(nF));
  pm.faceInput = faces;
  for (uint32_t i = 0; i < nF; ++i) {
    for (int c = 0; c < 3; ++c) {
      uint32_t r = uf.find(3 * i + c);
      if (rootVertex[r] == kNone) {
        rootVertex[r] = uint32_t(pm.vertexInput.size());
        uint32_t v = g.faces[faces[i]][c];
        pm.vertexInput.push_back(v);
        const Vec3& p = g.positions[v];
        pm.mesh.positions.insert(pm.mesh.positions.end(), {p.x, p.y, p.z});
      }
      pm.mesh.triangles[3 * i + c] = rootVertex[r];
    }
  }
  {  // pinched: an input vertex with two or more patch vertices
    thread_local Slots seen;
    seen.reserve(g.vertexCount);
    for (uint32_t v : pm.vertexInput) {
      if (seen.at[v] != kNone) pm.pinched = true;
      seen.set(v, 1);
    }
    seen.clear();
  }
  const long V = long(pm.vertexInput.size()), F = long(nF);
  const long E = (3 * F + long(boundaryHalfedges)) / 2;
  pm.eulerCharacteristic = int(V - E + F);
  if (!traceLoops) {
    // loops counted only: each boundary vertex has exactly one outgoing boundary halfedge
    std::vector<uint32_t> next(V, kNone);
    for (uint32_t h = 0; h < 3 * nF; ++h)
      if (heBoundary[h]) next[pm.mesh.triangles[h]] = pm.mesh.triangles[3 * (h / 3) + (h % 3 + 1) % 3];
    std::vector<uint8_t> seen(V, 0);
    for (long v = 0; v < V; ++v) {
      if (next[v] == kNone || seen[v]) continue;
      pm.boundaryLoops.emplace_back();
      uint32_t w = uint32_t(v);
      for (long guard = 0; !seen[w] && guard <= V; ++guard) {
        seen[w] = 1;
        w = next[w];
        if (w == kNone) break;
      }
    }
    return pm;
  }
  std::vector<uint32_t> outHe(V, kNone);
  for (uint32_t h = 0; h < 3 * nF; ++h)
    if (heBoundary[h]) {
      uint32_t v = pm.mesh.triangles[h];
      if (outHe[v] != kNone)
        fail(Code::InternalError, Stage::Segment, "patch boundary vertex with two outgoing boundary edges");
      outHe[v] = h;
    }
  std::vector<uint8_t> seen(3 * size_t(nF), 0);
  for (uint32_t h0 = 0; h0 < 3 * nF; ++h0) {
    if (!heBoundary[h0] || seen[h0]) continue;
    std::vector<PatchMesh::BoundaryHalfedge> loop;
    uint32_t h = h0;
    for (uint32_t guard = 0; !seen[h]; ++guard) {
      if (guard > 3 * nF) fail(Code::InternalError, Stage::Segment, "patch boundary loop does not close");
      seen[h] = 1;
      loop.push_back({h / 3, uint8_t(h % 3)});
      uint32_t to = pm.mesh.triangles[3 * (h / 3) + (h % 3 + 1) % 3];
      h = outHe[to];
      if (h == kNone) fail(Code::InternalError, Stage::Segment, "patch boundary loop is open");
    }
    if (h != h0) fail(Code::InternalError, Stage::Segment, "patch boundary loops merge");
    pm.boundaryLoops.push_back(std::move(loop));
  }
  return pm;
}

bool isDiskRegion(const EdgeGraph& g, const std::vector<uint8_t>& isCurve, const std::vector<uint32_t>& faces) {
  if (faces.empty()) return false;
  thread_local Slots inside;  // input face -> 1
  thread_local Slots next;    // input vertex -> the head of its outgoing boundary halfedge
  thread_local Slots vertex;  // input vertex of the region -> 1
  inside.reserve(g.faceCount);
  next.reserve(g.vertexCount);
  vertex.reserve(g.vertexCount);
  struct Clear {
    ~Clear() { inside.clear(), next.clear(), vertex.clear(); }
  } clear;
  for (const uint32_t f : faces) inside.set(f, 1);
  // Without a pinch each input vertex is one patch vertex, so χ = V − E + F over input vertices
  // with E = (3F + B) / 2 (B boundary halfedges), and each border vertex has one outgoing
  // boundary halfedge; a second one at a vertex is a second wedge there, a pinch (which the
  // count and the walk below would reject too: the earliest exit).
  size_t boundary = 0;
  for (const uint32_t f : faces)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = g.faces[f][c];
      vertex.set(a, 1);
      const uint32_t e = g.faceEdges[f][c];
      const uint32_t other = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
      if (!isCurve[e] && other != kNone && inside.at[other] != kNone) continue;
      if (next.at[a] != kNone) return false;  // pinched
      next.set(a, g.faces[f][(c + 1) % 3]);
      ++boundary;
    }
  if (boundary == 0) return false;
  const long F = long(faces.size()), V = long(vertex.used.size()), E = (3 * F + long(boundary)) / 2;
  if (V - E + F != 1) return false;
  // one boundary loop: the walk from one border vertex meets all of them
  const uint32_t start = next.used.front();
  size_t steps = 0;
  uint32_t v = start;
  do {
    v = next.at[v];
    if (v == kNone || ++steps > boundary) return false;
  } while (v != start);
  return steps == boundary;
}

}  // namespace conformesh::features
