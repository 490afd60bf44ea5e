#include "features/sink_cuts.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/constants.h"
#include "features/close_junctions.h"
#include "features/cut_junctions.h"
#include "features/patch_mesh.h"

namespace conformesh::features {
namespace {

bool onCurve(const EdgeGraph& g, const Segmentation& seg, uint32_t v) {
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
    if (seg.isCurveEdge(g.vertexEdgeIds[k])) return true;
  return false;
}

// Edge e may carry the cut: on no curve, and beside patch p (both its faces in p, or, for the
// last step onto the border, one of them).
bool stepAllowed(const EdgeGraph& g, const Segmentation& seg, uint32_t e, uint32_t p, bool toBorder) {
  if (seg.isCurveEdge(e)) return false;
  int inside = 0;
  for (uint32_t f : g.edgeFaces[e]) inside += f != kNone && seg.facePatch[f] == p;
  return toBorder ? inside > 0 : inside == 2;
}

// The ring of interior vertex v: its neighbours in the order of its faces, each with the 3D angle
// from the first one; `total` the angle sum. Empty when the faces around v do not close a fan.
std::vector<std::pair<uint32_t, double>> ringAngles(const EdgeGraph& g, uint32_t v, double& total) {
  std::vector<std::pair<uint32_t, double>> ring;
  const uint32_t e0 = g.vertexEdgeIds[g.vertexEdgeStart[v]];
  uint32_t w = g.otherVertex(e0, v), f = g.edgeFaces[e0][0];
  const uint32_t valence = g.vertexEdgeStart[v + 1] - g.vertexEdgeStart[v];
  double acc = 0;
  for (uint32_t step = 0; step < valence; ++step) {
    if (f == kNone) return {};
    ring.push_back({w, acc});
    int c = 0;
    while (c < 3 && g.faces[f][c] != v) ++c;
    if (c == 3) return {};
    acc += g.cornerAngle(f, c);
    const uint32_t next = g.faces[f][(c + 1) % 3] == w ? g.faces[f][(c + 2) % 3] : g.faces[f][(c + 1) % 3];
    const uint32_t e = g.findEdge(v, next);
    if (e == kNone) return {};
    f = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
    w = next;
  }
  if (w != g.otherVertex(e0, v)) return {};
  total = acc;
  return ring;
}

// The shortest path (input edges, from `sink`) inside patch p to the first vertex on a curve,
// whose first step goes to a vertex of `firstSteps` and which avoids the vertices of `avoid`;
// empty when there is none. Ties broken by vertex index, so the path is deterministic.
std::vector<uint32_t> pathToBorder(const EdgeGraph& g, const Segmentation& seg, uint32_t p, uint32_t sink,
                                   const std::vector<uint32_t>& firstSteps, const std::vector<uint32_t>& avoid) {
  struct Item {
    double d;
    uint32_t v;
    bool operator>(const Item& o) const { return d > o.d || (d == o.d && v > o.v); }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  std::unordered_map<uint32_t, std::pair<double, uint32_t>> best;  // vertex -> (distance, predecessor)
  for (uint32_t v : avoid) best[v] = {-1.0, kNone};                // never entered
  best[sink] = {0.0, kNone};
  for (uint32_t w : firstSteps) {
    const uint32_t e = g.findEdge(sink, w);
    if (e == kNone || best.count(w) || !stepAllowed(g, seg, e, p, onCurve(g, seg, w))) continue;
    best[w] = {g.edgeLength(e), sink};
    pq.push({g.edgeLength(e), w});
  }
  uint32_t end = kNone;
  while (!pq.empty()) {
    const Item it = pq.top();
    pq.pop();
    if (it.d > best[it.v].first) continue;
    if (onCurve(g, seg, it.v)) {
      end = it.v;
      break;
    }
    for (uint32_t k = g.vertexEdgeStart[it.v]; k < g.vertexEdgeStart[it.v + 1]; ++k) {
      const uint32_t e = g.vertexEdgeIds[k];
      const uint32_t w = g.otherVertex(e, it.v);
      if (!stepAllowed(g, seg, e, p, onCurve(g, seg, w))) continue;
      const double d = it.d + g.edgeLength(e);
      auto found = best.find(w);
      if (found != best.end() && !(d < found->second.first)) continue;
      best[w] = {d, it.v};
      pq.push({d, w});
    }
  }
  std::vector<uint32_t> path;
  for (uint32_t v = end; v != kNone; v = v == sink ? kNone : best[v].second) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

// Mark the paths' edges as cuts, make the junction repairs of a split over patch p, and keep the
// result only when p's faces now lie in two or more disks and there are more patches than before.
bool applyCuts(const EdgeGraph& g, Segmentation& seg, uint32_t p, const std::vector<const std::vector<uint32_t>*>& paths) {
  const std::vector<uint32_t> region = seg.patches[p];  // the cuts and their ends lie in it
  const size_t patchesBefore = seg.patches.size();
  const std::vector<EdgeKind> before = seg.edgeKind;
  const uint32_t cutEdges = seg.cutEdgeCount;
  for (const auto* path : paths)
    for (size_t i = 0; i + 1 < path->size(); ++i) {
      const uint32_t e = g.findEdge((*path)[i], (*path)[i + 1]);
      if (seg.edgeKind[e] != EdgeKind::None) continue;
      seg.edgeKind[e] = EdgeKind::Cut;
      ++seg.cutEdgeCount;
    }
  rebuildCurves(g, seg);
  improveCutJunctions(g, seg, seg.junctionScale, region);
  mergeCloseJunctions(g, seg, kCloseJunctionFactor * seg.junctionScale, region);
  straightenCutEars(g, seg, region, true);
  absorbCutSlivers(g, seg, seg.angleBoundDeg * kPi / 180, region);
  moveNarrowCutWedges(g, seg, seg.angleBoundDeg * kPi / 180, region);
  bool ok = patchesOver(seg, region) >= 2 && seg.patches.size() > patchesBefore;
  if (ok) {
    const std::vector<uint8_t> mask = seg.curveMask();
    std::vector<uint32_t> parts;
    for (uint32_t f : region) parts.push_back(seg.facePatch[f]);
    std::sort(parts.begin(), parts.end());
    parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
    for (uint32_t q : parts) ok = ok && extractPatch(g, mask, seg.patches[q], false).isDisk();
  }
  if (!ok) {
    seg.edgeKind = before;
    seg.cutEdgeCount = cutEdges;
    rebuildCurves(g, seg);
  }
  return ok;
}

// cutThroughSink and cutThroughSpike: `balanced` asks the second path to leave at least 3/8 of
// the angle sum away from the first, else it leaves through the most opposite neighbour.
bool cutThroughVertex(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, bool balanced, double minDepth) {
  if (p >= seg.patches.size() || sink >= g.vertexCount || onCurve(g, seg, sink)) return false;
  double theta = 0;
  const auto ring = ringAngles(g, sink, theta);
  if (ring.empty()) return false;
  std::vector<uint32_t> all;
  for (const auto& r : ring) all.push_back(r.first);
  const std::vector<uint32_t> first = pathToBorder(g, seg, p, sink, all, {});
  if (first.size() < 2) return false;
  if (minDepth > 0) {  // the nearest border is the first path's end
    double depth = 0;
    for (size_t i = 0; i + 1 < first.size(); ++i) depth += norm(g.positions[first[i + 1]] - g.positions[first[i]]);
    if (depth < minDepth) return false;
  }
  double a1 = 0;
  for (const auto& [w, a] : ring)
    if (w == first[1]) a1 = a;
  // the second path leaves the sink roughly opposite the first, or through the most opposite
  // neighbour that leaves each side minWedge
  std::vector<uint32_t> opposite;
  double mostAround = 0;
  uint32_t most = kNone;
  for (const auto& [w, a] : ring) {
    const double d = std::abs(a - a1), around = std::min(d, theta - d);
    if (balanced && around >= 0.375 * theta && around >= minWedge) opposite.push_back(w);
    if (around >= minWedge && around > mostAround) mostAround = around, most = w;
  }
  if (!balanced && most != kNone) opposite.push_back(most);
  const std::vector<uint32_t> avoid(first.begin() + 1, first.end());
  const std::vector<uint32_t> second = pathToBorder(g, seg, p, sink, opposite, avoid);
  if (second.size() < 2) return false;
  return applyCuts(g, seg, p, {&first, &second});
}

}  // namespace

bool cutThroughSink(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, double minDepth) {
  return cutThroughVertex(g, seg, p, sink, minWedge, true, minDepth);
}

bool cutThroughSpike(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t tip, double minWedge) {
  return cutThroughVertex(g, seg, p, tip, minWedge, false, 0.0);
}

bool cutThroughWideCorner(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t v, double minWedge) {
  if (p >= seg.patches.size() || v >= g.vertexCount || !onCurve(g, seg, v)) return false;
  // the wedge of p at v (a disk has one): from a curve edge beside one of p's faces, face by face
  // round v through p's faces to the next curve edge; its inner ring vertices with their angle
  // from the first edge
  uint32_t f = kNone, w = kNone;
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1] && f == kNone; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (!seg.isCurveEdge(e)) continue;
    for (uint32_t fe : g.edgeFaces[e])
      if (fe != kNone && seg.facePatch[fe] == p) f = fe, w = g.otherVertex(e, v);
  }
  if (f == kNone) return false;
  std::vector<std::pair<uint32_t, double>> inner;
  double wedge = 0;
  const uint32_t valence = g.vertexEdgeStart[v + 1] - g.vertexEdgeStart[v];
  for (uint32_t step = 0; step <= valence; ++step) {
    int c = 0;
    while (c < 3 && g.faces[f][c] != v) ++c;
    if (c == 3) return false;
    wedge += g.cornerAngle(f, c);
    const uint32_t next = g.faces[f][(c + 1) % 3] == w ? g.faces[f][(c + 2) % 3] : g.faces[f][(c + 1) % 3];
    const uint32_t e = g.findEdge(v, next);
    if (e == kNone) return false;
    if (seg.isCurveEdge(e)) break;
    inner.push_back({next, wedge});
    f = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
    if (f == kNone || seg.facePatch[f] != p) return false;
    w = next;
  }
  // the path leaves v near the middle of the wedge, each side at least 3/8 of it and minWedge
  std::vector<uint32_t> middle;
  for (const auto& [x, a] : inner)
    if (std::min(a, wedge - a) >= std::max(0.375 * wedge, minWedge)) middle.push_back(x);
  const std::vector<uint32_t> path = pathToBorder(g, seg, p, v, middle, {});
  if (path.size() < 2) return false;
  return applyCuts(g, seg, p, {&path});
}

}  // namespace conformesh::features
