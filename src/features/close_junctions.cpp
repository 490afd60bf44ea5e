#include "features/close_junctions.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "features/patch_mesh.h"
#include "features/wedges.h"

namespace conformesh::features {
namespace {

// An edge's kind before a tentative change, to undo it.
struct KindChange {
  uint32_t edge;
  EdgeKind before;
};

// The faces of `patches` regrouped across the edges that are not curves now: as many groups as
// patches, each a disk. seen: per input face, 0 outside a call (a scratch the caller keeps, so that
// a call costs the patches, not the mesh).
bool sameDisks(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint8_t>& mask,
               const std::vector<uint32_t>& patches, std::vector<uint8_t>& seen) {
  const auto inPatches = [&](uint32_t f) { return std::find(patches.begin(), patches.end(), seg.facePatch[f]) != patches.end(); };
  std::vector<uint32_t> stack, group, marked;
  size_t groups = 0;
  bool same = true;
  for (size_t k = 0; k < patches.size() && same; ++k)
    for (const uint32_t f0 : seg.patches[patches[k]]) {
      if (seen[f0]) continue;
      if (++groups > patches.size()) {
        same = false;
        break;
      }
      seen[f0] = 1;
      marked.push_back(f0);
      stack.assign(1, f0);
      group.clear();
      while (!stack.empty()) {
        const uint32_t f = stack.back();
        stack.pop_back();
        group.push_back(f);
        for (uint32_t e : g.faceEdges[f]) {
          if (mask[e]) continue;
          const uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
          if (o != kNone && !seen[o] && inPatches(o)) {
            seen[o] = 1;
            marked.push_back(o);
            stack.push_back(o);
          }
        }
      }
      if (!isDiskRegion(g, mask, group)) {
        same = false;
        break;
      }
    }
  for (const uint32_t f : marked) seen[f] = 0;
  return same && groups == patches.size();
}

}  // namespace

uint32_t mergeCloseJunctions(const EdgeGraph& g, Segmentation& seg, double minLength, const std::vector<uint32_t>& region) {
  if (!(minLength > 0)) return 0;
  std::vector<uint8_t> inRegion(g.faceCount, region.empty() ? 1 : 0);
  for (uint32_t f : region) inRegion[f] = 1;
  constexpr int kPasses = 4;             // hard cap; one merge per patch and pass
  const double radius = 4 * minLength;   // how far a moved cut's new stretch may reach
  std::vector<uint8_t> mask = seg.curveMask();
  std::vector<uint32_t> valence(g.vertexCount, 0);
  std::vector<double> dist(g.vertexCount, INFINITY);
  std::vector<uint32_t> predEdge(g.vertexCount, kNone), seen;
  std::vector<uint8_t> changed(g.vertexCount, 0);
  std::vector<uint8_t> seenFace(g.faceCount, 0);  // sameDisks' scratch
  std::vector<KindChange> log;
  const auto setKind = [&](uint32_t e, EdgeKind kind) {
    log.push_back({e, seg.edgeKind[e]});
    const bool was = mask[e] != 0, is = kind != EdgeKind::None;
    seg.edgeKind[e] = kind;
    mask[e] = is;
    if (was != is)
      for (uint32_t v : g.edgeVerts[e]) valence[v] = is ? valence[v] + 1 : valence[v] - 1;
  };
  const auto undo = [&]() {
    for (size_t i = log.size(); i-- > 0;) {
      const uint32_t e = log[i].edge;
      const bool was = mask[e] != 0, is = log[i].before != EdgeKind::None;
      seg.edgeKind[e] = log[i].before;
      mask[e] = is;
      if (was != is)
        for (uint32_t v : g.edgeVerts[e]) valence[v] = is ? valence[v] + 1 : valence[v] - 1;
    }
    log.clear();
  };
  WedgeScratch scratch;
  const auto wedgeAt = [&](uint32_t v) { return smallestWedge(g, v, [&](uint32_t e) { return mask[e] != 0; }, scratch); };
  // the shortest path of non-curve edges from u to y (no hairpin; no curve vertex on it but y),
  // from y back to u; empty when y is out of reach
  const auto pathTo = [&](uint32_t u, uint32_t back0, uint32_t y) {
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    dist[u] = 0;
    seen.push_back(u);
    pq.push({0.0, u});
    while (!pq.empty()) {
      auto [d, x] = pq.top();
      pq.pop();
      if (d > dist[x] || x == y) continue;
      for (uint32_t k = g.vertexEdgeStart[x]; k < g.vertexEdgeStart[x + 1]; ++k) {
        const uint32_t e = g.vertexEdgeIds[k];
        const uint32_t z = g.otherVertex(e, x);
        if (mask[e] || z == u || (valence[z] > 0 && z != y)) continue;
        const uint32_t back = x == u ? back0 : g.otherVertex(predEdge[x], x);
        if (back != kNone && angleBetween(g.positions[back] - g.positions[x], g.positions[z] - g.positions[x]) < kNarrowCutWedge) continue;
        const double nd = d + g.edgeLength(e);
        if (nd < dist[z] && nd <= radius) {
          if (std::isinf(dist[z])) seen.push_back(z);
          dist[z] = nd;
          predEdge[z] = e;
          pq.push({nd, z});
        }
      }
    }
    std::vector<uint32_t> path;
    if (std::isfinite(dist[y]))
      for (uint32_t x = y; x != u; x = g.otherVertex(predEdge[x], x)) path.push_back(x);
    if (!path.empty()) path.push_back(u);
    for (uint32_t x : seen) dist[x] = INFINITY, predEdge[x] = kNone;
    seen.clear();
    return path;
  };
  uint32_t total = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    std::fill(valence.begin(), valence.end(), 0);
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (mask[e]) ++valence[g.edgeVerts[e][0]], ++valence[g.edgeVerts[e][1]];
    std::fill(changed.begin(), changed.end(), 0);
    std::vector<uint8_t> usedPatch(seg.patches.size(), 0);
    std::vector<std::vector<std::pair<uint32_t, int>>> ends(g.vertexCount);  // (curve, 0: starts / 1: ends there)
    for (uint32_t ci = 0; ci < seg.curves.size(); ++ci) {
      ends[seg.curves[ci].vertices.front()].push_back({ci, 0});
      ends[seg.curves[ci].vertices.back()].push_back({ci, 1});
    }
    // shortest curves first
    std::vector<uint32_t> order;
    for (uint32_t ci = 0; ci < seg.curves.size(); ++ci)
      if (seg.curves[ci].length < minLength && inRegion[g.edgeFaces[seg.curves[ci].edges[0]][0]]) order.push_back(ci);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return seg.curves[a].length < seg.curves[b].length; });
    uint32_t merged = 0;
    for (uint32_t ci : order) {
      const Curve& c = seg.curves[ci];
      const uint32_t A = c.vertices.front(), B = c.vertices.back();
      if (A == B || changed[A] || changed[B]) continue;
      bool done = false;
      for (int dir = 0; dir < 2 && !done; ++dir) {
        const uint32_t X = dir == 0 ? B : A, Y = dir == 0 ? A : B;
        // the other curves at X: features and boundaries stay, cuts may move to Y
        std::vector<std::pair<uint32_t, int>> cuts;
        size_t stay = 0;
        bool ok = true;
        for (auto [cj, ej] : ends[X]) {
          if (cj == ci) continue;
          const Curve& o = seg.curves[cj];
          if (o.kind != EdgeKind::Cut) {
            ++stay;
            continue;
          }
          const uint32_t far = ej ? o.vertices.front() : o.vertices.back();
          if (far == X || far == Y) ok = false;  // a loop, or a second curve between X and Y
          cuts.push_back({cj, ej});
        }
        if (!ok || cuts.empty()) continue;
        // X must end as no corner: no curve (c a cut, dropped, and every cut moved), or a smooth
        // point of one kind of curve: the two that stay, or c and the one cut left with it
        struct Plan {
          bool dropC;
          uint32_t keep;  // index in cuts of the cut left at X, or kNone
        };
        std::vector<Plan> plans;
        if (c.kind == EdgeKind::Cut && stay == 0)
          for (uint32_t r = 0; r < cuts.size(); ++r) plans.push_back({false, r});
        if (c.kind == EdgeKind::Cut && (stay == 0 || stay == 2)) plans.push_back({true, kNone});
        if (c.kind != EdgeKind::Cut && stay == 1) plans.push_back({false, kNone});
        for (const Plan& plan : plans) {
          std::vector<std::pair<uint32_t, int>> moved;
          for (uint32_t r = 0; r < cuts.size(); ++r)
            if (r != plan.keep) moved.push_back(cuts[r]);
          std::vector<uint32_t> touched = {c.patches[0], c.patches[1]};
          for (auto [cj, ej] : moved) touched.insert(touched.end(), {seg.curves[cj].patches[0], seg.curves[cj].patches[1]});
          std::sort(touched.begin(), touched.end());
          touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
          if (!touched.empty() && touched.back() == kNone) touched.pop_back();
          bool busy = false;
          for (uint32_t p : touched) busy = busy || usedPatch[p];
          for (auto [cj, ej] : moved)
            for (uint32_t x : seg.curves[cj].vertices) busy = busy || changed[x];
          if (busy) break;
          const double before = std::min({wedgeAt(X), wedgeAt(Y), kNarrowCutWedge});
          log.clear();
          if (plan.dropC)
            for (uint32_t e : c.edges) setKind(e, EdgeKind::None);
          // every moved cut loses its stretch near X first (X itself may then be on the way)
          std::vector<std::vector<uint32_t>> rest;  // per moved cut: its vertices from the new end u on
          for (auto [cj, ej] : moved) {
            std::vector<uint32_t> path = seg.curves[cj].vertices;  // from X
            if (ej) std::reverse(path.begin(), path.end());
            double len = 0;
            size_t k = 1;
            const double retreat = std::min(minLength, 0.5 * seg.curves[cj].length);
            for (; k + 1 < path.size(); ++k) {
              len += norm(g.positions[path[k]] - g.positions[path[k - 1]]);
              if (len >= retreat) break;
            }
            for (size_t i = 0; i < k; ++i) setKind(g.findEdge(path[i], path[i + 1]), EdgeKind::None);
            rest.emplace_back(path.begin() + long(k), path.end());
          }
          std::vector<uint32_t> check = {Y};  // vertices whose wedge is judged after
          for (const auto& r : rest) {
            const std::vector<uint32_t> np = pathTo(r[0], r.size() > 1 ? r[1] : kNone, Y);
            if (np.empty()) {
              ok = false;
              break;
            }
            for (size_t i = 0; i + 1 < np.size(); ++i) setKind(g.findEdge(np[i], np[i + 1]), EdgeKind::Cut);
            check.insert(check.end(), np.begin() + 1, np.end());
          }
          // a path from a cut's far end (a corner) may run through a patch beside neither curve:
          // every patch beside a changed edge is judged, and must be free this pass
          if (ok) {
            for (const KindChange& kc : log)
              for (uint32_t f : g.edgeFaces[kc.edge])
                if (f != kNone) touched.push_back(seg.facePatch[f]);
            std::sort(touched.begin(), touched.end());
            touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
            for (uint32_t p : touched) ok = ok && !usedPatch[p];
          }
          if (ok && (valence[X] == 0 || valence[X] == 2) && sameDisks(g, seg, mask, touched, seenFace)) {
            double now = INFINITY;
            for (uint32_t v : check) now = std::min(now, wedgeAt(v));
            if (valence[X] == 2) now = std::min(now, wedgeAt(X));
            ok = now >= before;
          } else {
            ok = false;
          }
          if (!ok) {
            undo();
            ok = true;
            continue;
          }
          for (const KindChange& kc : log)
            for (uint32_t v : g.edgeVerts[kc.edge]) changed[v] = 1;
          changed[X] = changed[Y] = 1;
          for (uint32_t p : touched) usedPatch[p] = 1;
          log.clear();
          ++merged;
          done = true;
          break;
        }
      }
    }
    if (merged == 0) break;
    total += merged;
    rebuildCurves(g, seg);
  }
  seg.cutEdgeCount = 0;
  for (EdgeKind kd : seg.edgeKind) seg.cutEdgeCount += kd == EdgeKind::Cut;
  return total;
}

}  // namespace conformesh::features
