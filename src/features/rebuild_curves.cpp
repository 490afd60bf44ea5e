// Curves, corners and patches rebuilt from the edge kinds (segmentation.h rebuildCurves).
//
// Splitting a patch, rerouting a cut or undoing either changes a few edges of one region, and
// each is followed by a rebuild: rebuilding the whole mesh each time made a mesh of 100 patch
// splits spend most of its segmentation there. A rebuild retraces only the curves through the
// edges that changed (and those whose corners changed with them) and refloods only the patches
// beside them; the ids come out as a rebuild from scratch numbers them (curves in tracing order,
// patches by their smallest face), so the result is the same as one, byte for byte.
#include "features/segmentation.h"
#include "core/constants.h"
#include "core/detmath.h"

#include <algorithm>

namespace conformesh::features {
namespace {

// The order a rebuild from scratch traces a curve in: from its first corner (by vertex id, then
// by its edge's place around the vertex), then the closed loops without a corner by their
// smallest edge, each loop's two halves in turn.
constexpr uint64_t kLoopOrder = uint64_t(1) << 63;

uint64_t cornerOrder(uint32_t v, uint32_t slot) { return (uint64_t(v) << 32) | slot; }
uint64_t loopOrder(uint32_t e0, uint32_t half) { return kLoopOrder | (uint64_t(e0) << 1) | half; }

// Corner status of v (0 or 1; the loops' artificial corners are set by their trace): a vertex
// with other than two curve edges, two of different kinds, or two feature or boundary edges
// turning by more than turnLimit. Cuts are ours and smooth: they have no corners of their own
// (the staircase of input edges a cut follows would put a forced output vertex at every step).
uint8_t cornerStatus(const EdgeGraph& g, const Segmentation& seg, uint32_t v, double turnLimit) {
  uint32_t valence = 0, e1 = kNone, e2 = kNone;  // the two smallest curve edge ids around v
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (!seg.isCurveEdge(e)) continue;
    ++valence;
    if (e < e1) e2 = e1, e1 = e;
    else if (e < e2) e2 = e;
  }
  if (valence == 0) return 0;
  if (valence != 2 || seg.edgeKind[e1] != seg.edgeKind[e2]) return 1;
  if (seg.edgeKind[e1] == EdgeKind::Cut) return 0;
  const Vec3 a = g.positions[v] - g.positions[g.otherVertex(e1, v)];
  const Vec3 b = g.positions[g.otherVertex(e2, v)] - g.positions[v];
  return angleBetween(a, b) > turnLimit ? 1 : 0;
}

// The curve edge at v (a vertex with two) other than e.
uint32_t nextCurveEdge(const EdgeGraph& g, const Segmentation& seg, uint32_t v, uint32_t e) {
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t x = g.vertexEdgeIds[k];
    if (x != e && seg.isCurveEdge(x)) return x;
  }
  return kNone;
}

// The faces connected to f0 across edges that are not curve edges, given patch id p, in the
// order of a depth-first search from f0.
std::vector<uint32_t> floodFrom(const EdgeGraph& g, Segmentation& seg, uint32_t f0, uint32_t p, std::vector<uint32_t>& stack) {
  std::vector<uint32_t> faces;
  seg.facePatch[f0] = p;
  stack.push_back(f0);
  while (!stack.empty()) {
    const uint32_t f = stack.back();
    stack.pop_back();
    faces.push_back(f);
    for (uint32_t e : g.faceEdges[f]) {
      if (seg.isCurveEdge(e)) continue;
      const uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
      if (o != kNone && seg.facePatch[o] == kNone) {
        seg.facePatch[o] = p;
        stack.push_back(o);
      }
    }
  }
  return faces;
}

void sortUnique(std::vector<uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Trace the curves through the edges that are curve edges without a curve (edgeCurve kNone):
// first from the corners among `starts` (sorted), then the closed loops among `edges` (sorted).
// Every such edge must be reachable so: the callers pass every vertex whose corner status was
// recomputed and every edge whose curve was dropped. Returns the curves with their order.
std::vector<std::pair<uint64_t, Curve>> traceCurves(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& starts,
                                                    const std::vector<uint32_t>& edges, uint32_t firstId) {
  std::vector<std::pair<uint64_t, Curve>> out;
  auto trace = [&](uint32_t v, uint32_t e, uint64_t order) {
    Curve c;
    c.kind = seg.edgeKind[e];
    c.vertices.push_back(v);
    for (uint32_t guard = 0; guard <= g.edgeCount(); ++guard) {
      seg.edgeCurve[e] = firstId + uint32_t(out.size());
      c.edges.push_back(e);
      c.length += g.edgeLength(e);
      v = g.otherVertex(e, v);
      c.vertices.push_back(v);
      if (seg.vertexCorner[v]) break;
      e = nextCurveEdge(g, seg, v, e);
    }
    out.push_back({order, std::move(c)});
  };
  for (uint32_t v : starts) {
    if (seg.vertexCorner[v] != 1) continue;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
      const uint32_t e = g.vertexEdgeIds[k];
      if (seg.isCurveEdge(e) && seg.edgeCurve[e] == kNone) trace(v, e, cornerOrder(v, k - g.vertexEdgeStart[v]));
    }
  }
  // closed loops without a corner: two artificial corners, at the start and half the length
  for (uint32_t e0 : edges) {
    if (!seg.isCurveEdge(e0) || seg.edgeCurve[e0] != kNone) continue;
    uint32_t v = g.edgeVerts[e0][0], e = e0;
    std::vector<uint32_t> verts{v};
    std::vector<double> arc{0.0};
    for (uint32_t guard = 0; guard <= g.edgeCount(); ++guard) {
      arc.push_back(arc.back() + g.edgeLength(e));
      v = g.otherVertex(e, v);
      if (v == verts[0]) break;
      verts.push_back(v);
      e = nextCurveEdge(g, seg, v, e);
    }
    uint32_t half = 1;
    for (uint32_t i = 1; i < verts.size(); ++i)
      if (std::abs(arc[i] - 0.5 * arc.back()) < std::abs(arc[half] - 0.5 * arc.back())) half = i;
    seg.vertexCorner[verts[0]] = 2;
    seg.vertexCorner[verts[half]] = 2;
    trace(verts[0], e0, loopOrder(e0, 0));
    const uint32_t back = nextCurveEdge(g, seg, verts[0], e0);
    if (seg.edgeCurve[back] == kNone) trace(verts[0], back, loopOrder(e0, 1));
  }
  return out;
}

}  // namespace

void floodPatches(const EdgeGraph& g, Segmentation& seg) {
  seg.facePatch.assign(g.faceCount, kNone);
  seg.patches.clear();
  std::vector<uint32_t> stack;
  for (uint32_t f0 = 0; f0 < g.faceCount; ++f0)
    if (seg.facePatch[f0] == kNone) seg.patches.push_back(floodFrom(g, seg, f0, uint32_t(seg.patches.size()), stack));
  seg.builtKind.clear();  // the curves were not rebuilt with the patches
}

void rebuildCurves(const EdgeGraph& g, Segmentation& seg) {
  const double turnLimit = seg.cornerTurnDeg * kPi / 180.0;
  const uint32_t ne = g.edgeCount();
  const bool scratch = seg.builtKind.size() != ne || seg.edgeCurve.size() != ne || seg.vertexCorner.size() != g.vertexCount ||
                       seg.facePatch.size() != g.faceCount;
  std::vector<uint32_t> changed;  // edges whose kind differs from the one the curves were built from
  if (!scratch) {
    for (uint32_t e = 0; e < ne; ++e)
      if (seg.edgeKind[e] != seg.builtKind[e]) changed.push_back(e);
    if (changed.empty()) return;
  }

  // The curves to drop (their edges are retraced): every curve through a changed edge or a vertex
  // of one, then, while a dropped curve's end changes its corner status, the curves at that end.
  std::vector<uint8_t> drop(seg.curves.size(), scratch ? 1 : 0);
  std::vector<uint32_t> work;    // vertices whose corner status is recomputed
  std::vector<uint32_t> edges;   // edges that may need a new curve
  if (scratch) {
    seg.edgeCurve.assign(ne, kNone);
    seg.vertexCorner.assign(g.vertexCount, 0);
    work.resize(g.vertexCount);
    for (uint32_t v = 0; v < g.vertexCount; ++v) work[v] = v;
    edges.resize(ne);
    for (uint32_t e = 0; e < ne; ++e) edges[e] = e;
    for (uint32_t v : work) seg.vertexCorner[v] = cornerStatus(g, seg, v, turnLimit);
  } else {
    std::vector<uint32_t> todo;  // curves dropped whose ends are not yet looked at
    const auto dropCurve = [&](uint32_t c) {
      if (c != kNone && !drop[c]) drop[c] = 1, todo.push_back(c);
    };
    for (uint32_t e : changed) {
      dropCurve(seg.edgeCurve[e]);
      for (uint32_t v : g.edgeVerts[e]) {
        work.push_back(v);
        for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) dropCurve(seg.edgeCurve[g.vertexEdgeIds[k]]);
      }
    }
    sortUnique(work);
    std::vector<uint32_t> looked = work;  // vertices whose status is settled (sorted)
    std::vector<std::pair<uint32_t, uint8_t>> status;
    for (uint32_t v : work) status.push_back({v, cornerStatus(g, seg, v, turnLimit)});
    while (!todo.empty()) {
      const uint32_t c = todo.back();
      todo.pop_back();
      for (uint32_t v : {seg.curves[c].vertices.front(), seg.curves[c].vertices.back()}) {
        const auto at = std::lower_bound(looked.begin(), looked.end(), v);
        if (at != looked.end() && *at == v) continue;
        looked.insert(at, v);
        const uint8_t s = cornerStatus(g, seg, v, turnLimit);
        status.push_back({v, s});
        if (s != seg.vertexCorner[v])  // the curves ending here now continue through it, or stop
          for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) dropCurve(seg.edgeCurve[g.vertexEdgeIds[k]]);
      }
    }
    work = looked;
    for (const auto& [v, s] : status) seg.vertexCorner[v] = s;
    edges = changed;
    for (uint32_t c = 0; c < seg.curves.size(); ++c)
      if (drop[c])
        for (uint32_t e : seg.curves[c].edges) seg.edgeCurve[e] = kNone, edges.push_back(e);
    for (uint32_t e : changed) seg.edgeCurve[e] = kNone;
    sortUnique(edges);
  }

  // Kept curves and new ones, in the order a rebuild from scratch traces them.
  std::vector<std::pair<uint64_t, Curve>> all;
  for (uint32_t c = 0; c < seg.curves.size(); ++c)
    if (!drop[c]) all.push_back({seg.curves[c].order, std::move(seg.curves[c])});
  const uint32_t firstNew = uint32_t(all.size());
  for (auto& t : traceCurves(g, seg, work, edges, firstNew)) all.push_back(std::move(t));
  std::vector<uint32_t> oldId(all.size());  // index in `all` before sorting = the id edgeCurve holds
  for (uint32_t i = 0; i < all.size(); ++i) oldId[i] = i;
  std::sort(oldId.begin(), oldId.end(), [&](uint32_t a, uint32_t b) { return all[a].first < all[b].first; });
  seg.curves.clear();
  for (uint32_t id = 0; id < oldId.size(); ++id) {
    Curve c = std::move(all[oldId[id]].second);
    c.order = all[oldId[id]].first;
    for (uint32_t e : c.edges) seg.edgeCurve[e] = id;
    seg.curves.push_back(std::move(c));
  }

  // Patches: reflood those beside a changed edge, then number all by their smallest face.
  if (scratch) {
    floodPatches(g, seg);
  } else {
    std::vector<uint32_t> stale;
    for (uint32_t e : changed)
      for (uint32_t f : g.edgeFaces[e])
        if (f != kNone) stale.push_back(seg.facePatch[f]);
    sortUnique(stale);
    std::vector<uint32_t> faces;
    std::vector<std::vector<uint32_t>> patches;
    for (uint32_t p = 0, s = 0; p < seg.patches.size(); ++p) {
      if (s < stale.size() && stale[s] == p) {
        ++s;
        faces.insert(faces.end(), seg.patches[p].begin(), seg.patches[p].end());
      } else {
        patches.push_back(std::move(seg.patches[p]));
      }
    }
    for (uint32_t f : faces) seg.facePatch[f] = kNone;
    std::sort(faces.begin(), faces.end());
    std::vector<uint32_t> stack;
    for (uint32_t f : faces)
      if (seg.facePatch[f] == kNone) patches.push_back(floodFrom(g, seg, f, 0, stack));
    // a patch's depth-first list starts at its smallest face
    std::sort(patches.begin(), patches.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });
    seg.patches = std::move(patches);
    for (uint32_t p = 0; p < seg.patches.size(); ++p)
      for (uint32_t f : seg.patches[p]) seg.facePatch[f] = p;
  }
  for (auto& c : seg.curves) {
    const auto& fs = g.edgeFaces[c.edges[0]];
    c.patches = {fs[0] == kNone ? kNone : seg.facePatch[fs[0]], fs[1] == kNone ? kNone : seg.facePatch[fs[1]]};
  }
  seg.builtKind = seg.edgeKind;
}

}  // namespace conformesh::features
