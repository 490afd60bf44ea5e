#include "features/sink_cuts.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>
#include <vector>

#include "core/constants.h"
#include "features/cut_junctions.h"
#include "features/patch_mesh.h"

namespace conformesh::features {
namespace {

bool onCurve(const EdgeGraph& g, const Segmentation& seg, uint32_t v) { return curveValence(g, seg, v) > 0; }

// v is on patch p's border: on a curve other than an inner one (Segmentation::isInnerCurve).
bool onBorder(const EdgeGraph& g, const Segmentation& seg, uint32_t v) {
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (seg.isCurveEdge(e) && !seg.isInnerEdge(e)) return true;
  }
  return false;
}

// Sinks one cut passes through besides its first: each costs two shortest-path searches over the
// patch, and a hand has five tips.
constexpr uint32_t kMaxChainSinks = 8;

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

// The 3D length of a path of vertices (+infinity for no path).
double pathLength(const EdgeGraph& g, const std::vector<uint32_t>& path) {
  if (path.size() < 2) return INFINITY;
  double d = 0;
  for (size_t i = 0; i + 1 < path.size(); ++i) d += norm(g.positions[path[i + 1]] - g.positions[path[i]]);
  return d;
}

// Where a cut's path may end: at any curve (Curve); at p's border, keeping off its inner curves
// (Border: a path ending on an inner curve parts nothing); at one of given vertices, keeping off
// every curve (Target).
enum class PathEnd { Curve, Border, Target };

// The shortest path (input edges, from `sink`) inside patch p to the first vertex where it may
// end (`end`; `targets` for PathEnd::Target), whose first step goes to a vertex of `firstSteps`
// and which avoids the vertices of `avoid`; empty when there is none. Ties broken by vertex
// index, so the path is deterministic.
std::vector<uint32_t> pathToBorder(const EdgeGraph& g, const Segmentation& seg, uint32_t p, uint32_t sink,
                                   const std::vector<uint32_t>& firstSteps, const std::vector<uint32_t>& avoid,
                                   PathEnd end = PathEnd::Curve, const std::vector<uint32_t>& targets = {}) {
  const auto isEnd = [&](uint32_t v) {
    return end == PathEnd::Curve    ? onCurve(g, seg, v)
           : end == PathEnd::Border ? onBorder(g, seg, v)
                                    : std::find(targets.begin(), targets.end(), v) != targets.end();
  };
  const auto allowed = [&](uint32_t e, uint32_t w) {
    const bool last = end != PathEnd::Target && isEnd(w);
    return (last || !onCurve(g, seg, w)) && stepAllowed(g, seg, e, p, last);
  };
  struct Item {
    double d;
    uint32_t v;
    bool operator>(const Item& o) const { return d > o.d || (d == o.d && v > o.v); }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  // vertex -> (distance, predecessor), for the vertices reached (avoided ones at -1: never
  // entered); dense and kept by the thread, cleared over the vertices reached, as a search over
  // a large patch runs several times per cut (a hash map was a third of a sink cut's time)
  struct Reached {
    std::vector<double> dist;
    std::vector<uint32_t> pred;
    std::vector<uint8_t> seen;
    std::vector<uint32_t> list;
    void set(uint32_t v, double d, uint32_t from) {
      if (!seen[v]) seen[v] = 1, list.push_back(v);
      dist[v] = d, pred[v] = from;
    }
  };
  thread_local Reached best;
  if (best.seen.size() < g.vertexCount) best.dist.resize(g.vertexCount), best.pred.resize(g.vertexCount), best.seen.resize(g.vertexCount, 0);
  struct Clear {
    Reached& r;
    ~Clear() {
      for (const uint32_t v : r.list) r.seen[v] = 0;
      r.list.clear();
    }
  } clear{best};
  for (uint32_t v : avoid) best.set(v, -1.0, kNone);
  best.set(sink, 0.0, kNone);
  for (uint32_t w : firstSteps) {
    const uint32_t e = g.findEdge(sink, w);
    if (e == kNone || best.seen[w] || !allowed(e, w)) continue;
    best.set(w, g.edgeLength(e), sink);
    pq.push({g.edgeLength(e), w});
  }
  uint32_t last = kNone;
  while (!pq.empty()) {
    const Item it = pq.top();
    pq.pop();
    if (it.d > best.dist[it.v]) continue;
    if (isEnd(it.v)) {
      last = it.v;
      break;
    }
    for (uint32_t k = g.vertexEdgeStart[it.v]; k < g.vertexEdgeStart[it.v + 1]; ++k) {
      const uint32_t e = g.vertexEdgeIds[k];
      const uint32_t w = g.otherVertex(e, it.v);
      if (!allowed(e, w)) continue;
      const double d = it.d + g.edgeLength(e);
      if (best.seen[w] && !(d < best.dist[w])) continue;
      best.set(w, d, it.v);
      pq.push({d, w});
    }
  }
  std::vector<uint32_t> path;
  for (uint32_t v = last; v != kNone; v = v == sink ? kNone : best.pred[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

// Mark the paths' edges as cuts, make the junction repairs of a split over patch p (none that
// takes the cut off vertex `through`, the one the cut is for: its sink or wide wedge would stay
// inside a part, whose flattening fails again for the same reason; man: one cone cut three times
// over, each cut shaving 2-34 faces off the patch while the cone stayed inside), and keep the
// result only when p's faces now lie in two or more disks and there are more patches than before.
bool applyCuts(const EdgeGraph& g, Segmentation& seg, uint32_t p, const std::vector<const std::vector<uint32_t>*>& paths,
               uint32_t through) {
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
  if (patchesOver(seg, region) >= 2) repairNewCuts(g, seg, region, through);
  bool ok = patchesOver(seg, region) >= 2 && seg.patches.size() > patchesBefore;
  if (ok) {
    const std::vector<uint8_t> mask = seg.curveMask();
    std::vector<uint32_t> parts;
    for (uint32_t f : region) parts.push_back(seg.facePatch[f]);
    std::sort(parts.begin(), parts.end());
    parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
    for (uint32_t q : parts) ok = ok && isDiskRegion(g, mask, seg.patches[q]);
  }
  if (!ok) {
    seg.edgeKind = before;
    seg.cutEdgeCount = cutEdges;
    rebuildCurves(g, seg);
  }
  return ok;
}

// The neighbours of interior vertex v a path through v may leave by when it arrives from
// neighbour `from`: at least 3/8 of v's angle sum round from it (`balanced`), else the most
// opposite one; each side keeps minWedge. Empty when v has no closed fan.
std::vector<uint32_t> oppositeSteps(const EdgeGraph& g, uint32_t v, uint32_t from, double minWedge, bool balanced) {
  double theta = 0;
  const auto ring = ringAngles(g, v, theta);
  double a1 = 0;
  for (const auto& [w, a] : ring)
    if (w == from) a1 = a;
  std::vector<uint32_t> opposite;
  double mostAround = 0;
  uint32_t most = kNone;
  for (const auto& [w, a] : ring) {
    const double d = std::abs(a - a1), around = std::min(d, theta - d);
    if (balanced && around >= 0.375 * theta && around >= minWedge) opposite.push_back(w);
    if (around >= minWedge && around > mostAround) mostAround = around, most = w;
  }
  if (!balanced && most != kNone) opposite.push_back(most);
  return opposite;
}

// cutThroughSink and cutThroughSpike: `balanced` asks each path to leave a vertex it passes at
// least 3/8 of the angle sum away from where it came, else through the most opposite neighbour.
// `others`: further sinks the cut may pass through on its way back to the border (each the
// nearest left); `end` where its paths may end.
bool cutThroughVertex(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, bool balanced,
                      double minDepth, std::vector<uint32_t> others, PathEnd end) {
  if (p >= seg.patches.size() || sink >= g.vertexCount || onCurve(g, seg, sink)) return false;
  double theta = 0;
  const auto ring = ringAngles(g, sink, theta);
  if (ring.empty()) return false;
  std::vector<uint32_t> all;
  for (const auto& r : ring) all.push_back(r.first);
  const std::vector<uint32_t> first = pathToBorder(g, seg, p, sink, all, {}, end);
  if (first.size() < 2) return false;
  if (pathLength(g, first) < minDepth) return false;  // the nearest border is the first path's end
  // The way back from the sink: through the other sinks, each left opposite where the cut came
  // from, then to the border, each leg avoiding what the cut took before. One cut then puts
  // several sinks on the border where a cut per sink would make a patch per sink. A leg goes to
  // the nearest sink only when it is nearer than the border: one cut no longer than the two it
  // replaces (without that, a hand's finger tips chained through the webs left two halves whose
  // fingers overlapped in the plane, and man got more patches, not fewer).
  std::vector<std::vector<uint32_t>> legs{first};
  std::vector<uint32_t> avoid(first.begin() + 1, first.end());
  others.erase(std::remove_if(others.begin(), others.end(), [&](uint32_t v) { return v == sink || onCurve(g, seg, v); }), others.end());
  // each leg takes one sink off the list; kMaxChainSinks bounds the Dijkstra runs of a cut
  for (uint32_t at = sink, from = first[1], chained = 0;; ++chained) {
    if (chained >= kMaxChainSinks) others.clear();
    const std::vector<uint32_t> opposite = oppositeSteps(g, at, from, minWedge, balanced);
    std::vector<uint32_t> leg = others.empty() ? std::vector<uint32_t>{} : pathToBorder(g, seg, p, at, opposite, avoid, PathEnd::Target, others);
    std::vector<uint32_t> out = pathToBorder(g, seg, p, at, opposite, avoid, end);
    const bool toSink = leg.size() >= 2 && pathLength(g, leg) < pathLength(g, out);
    if (!toSink) leg = std::move(out);
    if (leg.size() < 2) break;
    avoid.insert(avoid.end(), leg.begin(), leg.end());
    legs.push_back(std::move(leg));
    if (!toSink) break;
    at = legs.back().back();
    from = legs.back()[legs.back().size() - 2];
    others.erase(std::remove(others.begin(), others.end(), at), others.end());
  }
  // no leg from the sink at all: its way to the border alone (the first leg's search) failed too
  if (legs.size() < 2) return false;
  const bool back = onCurve(g, seg, legs.back().back());
  if (back && legs.size() == 2) return applyCuts(g, seg, p, {&legs[0], &legs[1]}, sink);
  if (back) {
    std::vector<const std::vector<uint32_t>*> paths;
    for (const auto& leg : legs) paths.push_back(&leg);
    if (applyCuts(g, seg, p, paths, sink)) return true;
  }
  // a chain that does not get back to the border, or whose cut fails: the sink alone
  const std::vector<uint32_t> second =
      pathToBorder(g, seg, p, sink, oppositeSteps(g, sink, first[1], minWedge, balanced), std::vector<uint32_t>(first.begin() + 1, first.end()), end);
  return second.size() >= 2 && applyCuts(g, seg, p, {&first, &second}, sink);
}

// cutThroughVertex with paths ending at any curve; for a spike tip in a patch with inner curves,
// when that fails (a path ends on an inner curve and parts nothing), ending at its border: a tip
// left inside is cut off by the output (a sink left inside only costs triangles, and the longer
// cuts round inner curves made more patches and short junctions: ChineseDragon-10kv).
bool cutThroughVertex(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, bool balanced,
                      double minDepth, const std::vector<uint32_t>& others = {}) {
  if (cutThroughVertex(g, seg, p, sink, minWedge, balanced, minDepth, others, PathEnd::Curve)) return true;
  bool inner = false;
  for (uint32_t c = 0; c < seg.curves.size() && !inner; ++c) inner = seg.isInnerCurve(c) && seg.curves[c].patches[0] == p;
  return inner && !balanced && cutThroughVertex(g, seg, p, sink, minWedge, balanced, minDepth, others, PathEnd::Border);
}

}  // namespace

bool cutThroughSink(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, double minDepth,
                    const std::vector<uint32_t>& others) {
  return cutThroughVertex(g, seg, p, sink, minWedge, true, minDepth, others);
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
  return applyCuts(g, seg, p, {&path}, v);
}

}  // namespace conformesh::features
