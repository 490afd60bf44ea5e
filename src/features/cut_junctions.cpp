#include "features/cut_junctions.h"
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <queue>
#include <string>

#include "core/detmath.h"
#include "features/wedges.h"

namespace conformesh::features {
namespace {


// The point at arc length `len` along a vertex path (its last vertex when the path is shorter).
Vec3 pointAlong(const EdgeGraph& g, const std::vector<uint32_t>& path, double len) {
  double acc = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec3 a = g.positions[path[i - 1]], b = g.positions[path[i]];
    const double l = norm(b - a);
    if (l > 0 && acc + l >= len) return a + (b - a) * ((len - acc) / l);
    acc += l;
  }
  return g.positions[path.back()];
}

// The angle at which a cut (vertex path `cut`) meets another curve (`other`) at their common first
// vertex: the angle between their directions at the junction scale (dCut, dOther), or between
// their first edges where that is narrower than kNarrowCutWedge. A cut can arrive at the scale's
// angle through an input edge that leaves the curve at a few degrees (across a sliver): the patch
// between them then has that corner, and the refinement's segment splits crowd into it.
double endAngle(const EdgeGraph& g, const std::vector<uint32_t>& cut, const std::vector<uint32_t>& other, const Vec3& dCut,
                const Vec3& dOther) {
  const double scaleAngle = angleBetween(dCut, dOther);
  const Vec3& x = g.positions[cut[0]];
  const double edgeAngle = angleBetween(g.positions[cut[1]] - x, g.positions[other[1]] - x);
  return edgeAngle < kNarrowCutWedge ? std::min(scaleAngle, edgeAngle) : scaleAngle;
}

// The faces of patches A and B (as the last rebuild numbered them) regrouped across the edges that
// are not curves now: exactly two groups, each a disk. label: per input face, kNone outside a call
// (a scratch the caller keeps, so that a call costs the two patches, not the mesh).
bool splitsIntoTwoDisks(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint8_t>& mask, uint32_t A, uint32_t B,
                        std::vector<uint32_t>& label) {
  std::vector<std::vector<uint32_t>> groups;
  std::vector<uint32_t> stack;
  bool more = false;  // a third group
  for (const uint32_t P : {A, B})
    for (const uint32_t f0 : seg.patches[P]) {
      if (label[f0] != kNone) continue;
      if (groups.size() == 2) {
        more = true;
        break;
      }
      label[f0] = uint32_t(groups.size());
      groups.emplace_back();
      stack.push_back(f0);
      while (!stack.empty()) {
        const uint32_t f = stack.back();
        stack.pop_back();
        groups.back().push_back(f);
        for (uint32_t e : g.faceEdges[f]) {
          if (seg.isCurveEdge(e)) continue;
          const uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
          if (o != kNone && label[o] == kNone && (seg.facePatch[o] == A || seg.facePatch[o] == B)) {
            label[o] = label[f];
            stack.push_back(o);
          }
        }
      }
    }
  for (const auto& gr : groups)
    for (const uint32_t f : gr) label[f] = kNone;
  if (more || groups.size() != 2) return false;
  for (const auto& gr : groups)
    if (!isDiskRegion(g, mask, gr)) return false;
  return true;
}

// Whether the patches `ids` of seg (its curves rebuilt) are all disks.
bool patchesAreDisks(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint32_t>& ids) {
  const std::vector<uint8_t> mask = seg.curveMask();
  for (const uint32_t p : ids)
    if (!isDiskRegion(g, mask, seg.patches[p])) return false;
  return true;
}

// The safety net after moving cuts (curves rebuilt): every patch is still a disk, else the
// edge kinds are put back as they were. Returns whether the moves are kept. Every patch was a
// disk before, and one beside no edge whose kind changed has the same faces and borders as
// then: only the patches beside a changed edge are checked (not every patch at every split).
bool keepCutsIfAllDisks(const EdgeGraph& g, Segmentation& seg, const std::vector<EdgeKind>& original) {
  std::vector<uint32_t> touched;
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (seg.edgeKind[e] != original[e])
      for (uint32_t f : g.edgeFaces[e])
        if (f != kNone) touched.push_back(seg.facePatch[f]);
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  if (!patchesAreDisks(g, seg, touched)) {
    seg.edgeKind = original;
    rebuildCurves(g, seg);
    return false;
  }
  seg.cutEdgeCount = 0;
  for (EdgeKind kd : seg.edgeKind) seg.cutEdgeCount += kd == EdgeKind::Cut;
  return true;
}

// Edges sorted longest first (ties by index, so the order is the same on every platform).
void sortLongestFirst(const EdgeGraph& g, std::vector<uint32_t>& edges) {
  std::sort(edges.begin(), edges.end(), [&](uint32_t a, uint32_t b) {
    return g.edgeLength(a) > g.edgeLength(b) || (g.edgeLength(a) == g.edgeLength(b) && a < b);
  });
}

// A vertex of `ends` left with one curve edge ends a cut branch that no longer separates
// anything: the branch goes, edge by edge back to where it meets other curves, each edge handed
// to `drop` (which unmarks it). False, at once, when a branch ends in a feature or boundary edge
// (a feature's end would dangle) or more than `budget` edges would go (a negative budget: any).
template <class Drop>
bool pruneDanglingCuts(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint32_t>& ends, std::ptrdiff_t budget, Drop&& drop) {
  std::ptrdiff_t dropped = 0;
  for (uint32_t x : ends)
    for (;;) {
      uint32_t only = kNone, n = 0;
      for (uint32_t k = g.vertexEdgeStart[x]; k < g.vertexEdgeStart[x + 1]; ++k)
        if (seg.isCurveEdge(g.vertexEdgeIds[k])) only = g.vertexEdgeIds[k], ++n;
      if (n != 1) break;
      if (seg.edgeKind[only] != EdgeKind::Cut || dropped > budget) return false;
      drop(only);
      ++dropped;
      x = g.otherVertex(only, x);
    }
  return true;
}
}  // namespace

uint32_t improveCutJunctions(const EdgeGraph& g, Segmentation& seg, double scale, const std::vector<uint32_t>& region) {
  if (!(scale > 0)) return 0;
  std::vector<uint8_t> inRegion(g.faceCount, region.empty() ? 1 : 0);
  for (uint32_t f : region) inRegion[f] = 1;
  const double kAim = 60.0 * kPi / 180.0;   // ends meeting another curve below this are rerouted
  const double kGain = 5.0 * kPi / 180.0;   // a reroute must improve the angle by this much
  const int kPasses = 8;                     // one reroute per patch and pass
  const size_t kTries = 6;                   // landings tried per cut end
  const std::vector<EdgeKind> original = seg.edgeKind;
  std::vector<uint8_t> mask = seg.curveMask();  // kept in step with seg.edgeKind below
  auto setKind = [&](uint32_t e, EdgeKind kind) {
    seg.edgeKind[e] = kind;
    mask[e] = kind != EdgeKind::None;
  };
  std::vector<uint32_t> valence(g.vertexCount, 0);
  std::vector<double> dist(g.vertexCount, INFINITY);
  std::vector<uint32_t> predEdge(g.vertexCount, kNone), seen;
  std::vector<uint8_t> changed(g.vertexCount, 0), forbidden(g.vertexCount, 0);
  std::vector<uint32_t> faceLabel(g.faceCount, kNone);  // splitsIntoTwoDisks' scratch
  uint32_t total = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    std::fill(valence.begin(), valence.end(), 0);
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (seg.isCurveEdge(e)) ++valence[g.edgeVerts[e][0]], ++valence[g.edgeVerts[e][1]];
    std::fill(changed.begin(), changed.end(), 0);
    std::vector<uint8_t> usedPatch(seg.patches.size(), 0);
    // the curve ends at every corner: (curve, 0 = starts there / 1 = ends there)
    std::vector<std::vector<std::pair<uint32_t, int>>> ends(g.vertexCount);
    for (uint32_t ci = 0; ci < seg.curves.size(); ++ci) {
      ends[seg.curves[ci].vertices.front()].push_back({ci, 0});
      ends[seg.curves[ci].vertices.back()].push_back({ci, 1});
    }
    auto fromEnd = [&](uint32_t ci, int end) {
      std::vector<uint32_t> path = seg.curves[ci].vertices;
      if (end) std::reverse(path.begin(), path.end());
      return path;
    };
    uint32_t moved = 0;
    for (uint32_t ci = 0; ci < seg.curves.size(); ++ci) {
      const Curve& c = seg.curves[ci];
      if (c.kind != EdgeKind::Cut || c.patches[0] == kNone || c.patches[1] == kNone || c.patches[0] == c.patches[1])
        continue;
      if (!inRegion[g.edgeFaces[c.edges[0]][0]]) continue;  // a cut has faces on both sides
      const uint32_t A = c.patches[0], B = c.patches[1];
      for (int end = 0; end < 2; ++end) {
        // one reroute per patch and pass (patch ids are rebuilt between passes)
        if (usedPatch[A] || usedPatch[B]) break;
        const std::vector<uint32_t> path = fromEnd(ci, end);
        const uint32_t v = path[0];
        // a junction of three or more curve edges (an end joining a dangling feature stays)
        if (path.size() < 3 || valence[v] < 3) continue;
        bool stale = false;
        for (uint32_t x : path) stale = stale || changed[x];
        if (stale) continue;
        const double l = std::min(scale, 0.3 * c.length);
        const Vec3 d0 = pointAlong(g, path, l) - g.positions[v];
        double old = kPi;
        for (auto [cj, ej] : ends[v]) {
          if (cj == ci && ej == end) continue;
          std::vector<uint32_t> other = fromEnd(cj, ej);
          old = std::min(old, endAngle(g, path, other, d0, pointAlong(g, other, l) - g.positions[v]));
        }
        if (old >= kAim) continue;
        // u: the cut's vertex about 3·l from the end (never its far end)
        size_t k = 1;
        for (double acc = 0; k + 1 < path.size(); ++k) {
          acc += norm(g.positions[path[k]] - g.positions[path[k - 1]]);
          if (acc >= std::min(3 * l, 0.5 * c.length)) break;
        }
        if (k + 1 >= path.size()) continue;
        const uint32_t u = path[k];
        std::vector<uint32_t> oldEdges;
        for (size_t i = 0; i < k; ++i) {
          uint32_t e = g.findEdge(path[i], path[i + 1]);
          oldEdges.push_back(e);
          setKind(e, EdgeKind::None);
          --valence[path[i]], --valence[path[i + 1]];
        }
        for (size_t i = k + 1; i < path.size(); ++i) forbidden[path[i]] = 1;
        // Dijkstra from u through vertices on no curve; every smooth curve point it reaches is a
        // landing candidate (the nearest one meets its curve at about a right angle, but it may
        // be on another curve or next to a corner: each candidate's angle is measured)
        using Item = std::pair<double, uint32_t>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
        dist[u] = 0;
        seen.push_back(u);
        pq.push({0.0, u});
        std::vector<uint32_t> landings;
        const double radius = 12 * l;
        while (!pq.empty()) {
          auto [d, x] = pq.top();
          pq.pop();
          if (d > dist[x]) continue;
          if (x != u && valence[x] > 0) {
            landings.push_back(x);  // a landing point: the path does not go on through it
            continue;
          }
          for (uint32_t kk = g.vertexEdgeStart[x]; kk < g.vertexEdgeStart[x + 1]; ++kk) {
            const uint32_t e = g.vertexEdgeIds[kk];
            if (seg.isCurveEdge(e)) continue;
            const uint32_t y = g.otherVertex(e, x);
            if (y == u || forbidden[y] || changed[y]) continue;
            // a curve vertex is a landing point only when it is a smooth point of a curve
            if (valence[y] > 0 && (y == v || valence[y] != 2 || seg.vertexCorner[y])) continue;
            // no hairpin at x: the new cut must not turn back on itself there (on a fan of
            // needle faces a shortest path can, making a wedge of a degree or two). At u the
            // path continues the part of the cut that stays.
            const uint32_t back = x == u ? path[k + 1] : g.otherVertex(predEdge[x], x);
            if (angleBetween(g.positions[back] - g.positions[x], g.positions[y] - g.positions[x]) < kNarrowCutWedge) continue;
            const double nd = d + g.edgeLength(e);
            if (nd < dist[y] && nd <= radius) {
              if (std::isinf(dist[y])) seen.push_back(y);
              dist[y] = nd;
              predEdge[y] = e;
              pq.push({nd, y});
            }
          }
        }
        // the landings ranked (below); the first whose cut leaves two disks wins
        const auto inAB = [&](uint32_t q) { return q == A || q == B; };
        std::vector<std::pair<double, uint32_t>> ranked;
        for (uint32_t x : landings) {
          std::vector<uint32_t> cutPath;
          for (uint32_t y = x; y != u; y = g.otherVertex(predEdge[y], y)) cutPath.push_back(y);
          cutPath.push_back(u);
          cutPath.insert(cutPath.end(), path.begin() + long(k) + 1, path.end());
          const Vec3 dn = pointAlong(g, cutPath, l) - g.positions[x];
          uint32_t cj = kNone;
          for (uint32_t kk = g.vertexEdgeStart[x]; kk < g.vertexEdgeStart[x + 1] && cj == kNone; ++kk)
            if (seg.isCurveEdge(g.vertexEdgeIds[kk])) cj = seg.edgeCurve[g.vertexEdgeIds[kk]];
          // the landing curve must have exactly one side in the merged region A ∪ B, else the
          // new cut would leave a patch touching itself at the landing point
          if (cj == kNone || inAB(seg.curves[cj].patches[0]) == inAB(seg.curves[cj].patches[1])) continue;
          const auto& cv = seg.curves[cj].vertices;
          const auto it = std::find(cv.begin(), cv.end(), x);
          if (it == cv.end()) continue;
          std::vector<uint32_t> fwd(it, cv.end()), back(cv.begin(), it + 1);
          std::reverse(back.begin(), back.end());
          double now = kPi;
          for (const auto* side : {&fwd, &back})
            if (side->size() > 1) now = std::min(now, endAngle(g, cutPath, *side, dn, pointAlong(g, *side, l) - g.positions[x]));
          if (now > old + kGain) ranked.push_back({now, x});
        }
        // landings were found nearest first: those at kAim or more keep that order (the nearest
        // good one first), the others follow by angle, largest first
        std::stable_sort(ranked.begin(), ranked.end(), [&](const auto& p, const auto& q) {
          const bool gp = p.first >= kAim, gq = q.first >= kAim;
          if (gp != gq) return gp;
          return !gp && p.first > q.first;
        });
        bool commit = false;
        std::vector<uint32_t> newPath;  // from the landing point to u
        for (size_t r = 0; r < ranked.size() && r < kTries && !commit; ++r) {
          newPath.clear();
          for (uint32_t x = ranked[r].second; x != u; x = g.otherVertex(predEdge[x], x)) newPath.push_back(x);
          newPath.push_back(u);
          for (size_t i = 0; i + 1 < newPath.size(); ++i) {
            setKind(g.findEdge(newPath[i], newPath[i + 1]), EdgeKind::Cut);
            ++valence[newPath[i]], ++valence[newPath[i + 1]];
          }
          commit = splitsIntoTwoDisks(g, seg, mask, A, B, faceLabel);
          if (!commit)  // A and B share another curve that this cut leaves on one side
            for (size_t i = 0; i + 1 < newPath.size(); ++i) {
              setKind(g.findEdge(newPath[i], newPath[i + 1]), EdgeKind::None);
              --valence[newPath[i]], --valence[newPath[i + 1]];
            }
        }
        for (uint32_t x : seen) dist[x] = INFINITY, predEdge[x] = kNone;
        seen.clear();
        for (size_t i = k + 1; i < path.size(); ++i) forbidden[path[i]] = 0;
        if (commit) {
          for (uint32_t x : path) changed[x] = 1;
          for (uint32_t x : newPath) changed[x] = 1;
          usedPatch[A] = usedPatch[B] = 1;
          ++moved;
        }
        if (!commit) {
          for (size_t i = 0; i < k; ++i) {
            setKind(oldEdges[i], EdgeKind::Cut);
            ++valence[path[i]], ++valence[path[i + 1]];
          }
        }
      }
    }
    if (moved == 0) break;
    total += moved;
    rebuildCurves(g, seg);
  }
  if (total == 0 || !keepCutsIfAllDisks(g, seg, original)) return 0;
  seg.reroutedCutEnds += total;
  return total;
}

size_t patchesOver(const Segmentation& seg, const std::vector<uint32_t>& faces) {
  std::vector<uint32_t> ids;
  for (uint32_t f : faces) ids.push_back(seg.facePatch[f]);
  std::sort(ids.begin(), ids.end());
  return size_t(std::unique(ids.begin(), ids.end()) - ids.begin());
}

size_t largestShare(const Segmentation& seg, const std::vector<uint32_t>& faces) {
  std::vector<uint32_t> ids;
  for (uint32_t f : faces) ids.push_back(seg.facePatch[f]);
  std::sort(ids.begin(), ids.end());
  size_t most = 0;
  for (size_t i = 0, j = 0; i < ids.size(); i = j) {
    while (j < ids.size() && ids[j] == ids[i]) ++j;
    most = std::max(most, j - i);
  }
  return most;
}

uint32_t straightenCutEars(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& region, bool keepSplit) {
  const double kEar = kNarrowCutWedge;  // wedges below this are candidates
  const double kGain = 1.0 * kPi / 180.0;  // a move must raise the smallest wedge by this much
  constexpr int kPasses = 8;
  constexpr size_t kMaxFan = 64;  // faces in one wedge (needle fans)
  constexpr size_t kMaxPrune = 4096;  // edges one move may change, pruned branches included
  const std::vector<EdgeKind> original = seg.edgeKind;
  WedgeScratch scratch;
  auto isCurve = [&](uint32_t e) { return seg.isCurveEdge(e); };
  auto wedgeAround = [&](uint32_t v, const std::vector<uint32_t>& rim) {
    double m = smallestWedge(g, v, isCurve, scratch);
    for (uint32_t x : rim) m = std::min(m, smallestWedge(g, x, isCurve, scratch));
    return m;
  };
  auto valence = [&](uint32_t x) {
    uint32_t n = 0;
    for (uint32_t k = g.vertexEdgeStart[x]; k < g.vertexEdgeStart[x + 1]; ++k) n += seg.isCurveEdge(g.vertexEdgeIds[k]);
    return n;
  };
  auto onlyCuts = [&](uint32_t x) {
    for (uint32_t k = g.vertexEdgeStart[x]; k < g.vertexEdgeStart[x + 1]; ++k) {
      const EdgeKind kd = seg.edgeKind[g.vertexEdgeIds[k]];
      if (kd == EdgeKind::Feature || kd == EdgeKind::Boundary) return false;
    }
    return true;
  };
  // after rebuildCurves: the patches of the faces beside the edges es are disks
  std::vector<uint32_t> touched;
  auto touchedPatchesAreDisks = [&](const std::vector<uint32_t>& es) {
    touched.clear();
    for (uint32_t e : es)
      for (uint32_t f : g.edgeFaces[e])
        if (f != kNone) touched.push_back(seg.facePatch[f]);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    return patchesAreDisks(g, seg, touched);
  };
  std::vector<uint32_t> rim, rimEdges, toggled;
  // in face order, as the scan of the whole mesh: the moves depend on their order
  std::vector<uint32_t> faces(region);
  std::sort(faces.begin(), faces.end());
  const size_t scanned = region.empty() ? g.faceCount : faces.size();
  uint32_t total = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    uint32_t moved = 0;
    for (size_t i0 = 0; i0 < scanned; ++i0)
      for (int c0 = 0; c0 < 3; ++c0)
        for (int side = 0; side < 2; ++side) {
          // the wedge at v from the cut edge v-a, turning away from it face by face until the
          // next curve edge v-c; rim: a, ..., c (the far vertices of the wedge's faces)
          const uint32_t f0 = region.empty() ? uint32_t(i0) : faces[i0];
          const uint32_t v = g.faces[f0][c0], a = g.faces[f0][(c0 + 1 + side) % 3];
          const uint32_t ea = g.findEdge(v, a);
          if (ea == kNone || seg.edgeKind[ea] != EdgeKind::Cut) continue;
          uint32_t f = f0, b = g.faces[f0][(c0 + 2 - side) % 3];
          double angle = g.cornerAngle(f0, c0);
          rim.assign({a, b});
          uint32_t eb = g.findEdge(v, b);
          while (eb != kNone && !seg.isCurveEdge(eb) && angle < kEar && rim.size() <= kMaxFan) {
            const uint32_t nf = g.edgeFaces[eb][0] == f ? g.edgeFaces[eb][1] : g.edgeFaces[eb][0];
            if (nf == kNone) break;
            int cv = 0;
            while (cv < 3 && g.faces[nf][cv] != v) ++cv;
            if (cv == 3) break;
            const uint32_t x = g.faces[nf][(cv + 1) % 3] == b ? g.faces[nf][(cv + 2) % 3] : g.faces[nf][(cv + 1) % 3];
            angle += g.cornerAngle(nf, cv);
            rim.push_back(x);
            f = nf;
            b = x;
            eb = g.findEdge(v, x);
          }
          // (eb == ea: the walk went all the way round v, a cone of less than kEar)
          if (eb == kNone || eb == ea || !seg.isCurveEdge(eb) || !(angle < kEar)) continue;
          // the cut moves across the wedge's faces: every edge of their border toggles (the
          // edges at v stop being cuts; rim edges become cuts, or stop being cuts where the
          // rim already ran along one). No feature or boundary edge on the rim or at its inner
          // vertices.
          rimEdges.clear();
          bool ok = true, oldCutOnRim = false;
          for (size_t i = 0; i + 1 < rim.size() && ok; ++i) {
            const uint32_t e = g.findEdge(rim[i], rim[i + 1]);
            ok = e != kNone && (seg.edgeKind[e] == EdgeKind::None || seg.edgeKind[e] == EdgeKind::Cut) &&
                 (i == 0 || onlyCuts(rim[i]));
            oldCutOnRim = oldCutOnRim || (ok && seg.edgeKind[e] == EdgeKind::Cut);
            rimEdges.push_back(e);
          }
          const bool cutB = seg.edgeKind[eb] == EdgeKind::Cut;
          // v keeps no curve edge or at least two (a dangling end would be a slit)
          if (!ok || int(valence(v)) - 1 - int(cutB) == 1) continue;
          const double before = wedgeAround(v, rim);
          // the rim's ends as they were: a move may not leave one narrower than kEar and than it was
          // (the ear moved onto a curve's end, where a crease continues into the cut)
          const double beforeA = smallestWedge(g, rim.front(), isCurve, scratch);
          const double beforeC = smallestWedge(g, rim.back(), isCurve, scratch);
          toggled.clear();
          auto flipKind = [&](uint32_t e) { seg.edgeKind[e] = seg.edgeKind[e] == EdgeKind::Cut ? EdgeKind::None : EdgeKind::Cut; };
          auto toggle = [&](uint32_t e) {
            flipKind(e);
            toggled.push_back(e);
          };
          auto undo = [&]() {
            for (auto it = toggled.rbegin(); it != toggled.rend(); ++it) flipKind(*it);
          };
          toggle(ea);
          if (cutB) toggle(eb);
          for (uint32_t e : rimEdges) toggle(e);
          // a rim vertex left with one cut edge ends a branch that no longer separates
          // anything: the branch goes, back to where it meets other curves. A branch that would
          // leave a feature's end dangling keeps the old cut.
          ok = pruneDanglingCuts(g, seg, rim, std::ptrdiff_t(kMaxPrune) - std::ptrdiff_t(toggled.size()), toggle);
          ok = ok && wedgeAround(v, rim) > before + kGain;
          ok = ok && smallestWedge(g, rim.front(), isCurve, scratch) >= std::min(kEar, beforeA) &&
               smallestWedge(g, rim.back(), isCurve, scratch) >= std::min(kEar, beforeC);
          // a move that took an old cut off the rim or pruned a branch regroups faces of more
          // than two patches: it is kept only when every patch it touches stays a disk
          // (checked at once, so that one such move cannot undo all the others at the end)
          const bool regroups = oldCutOnRim || toggled.size() > size_t(1 + int(cutB)) + rimEdges.size();
          if (ok && regroups) {
            rebuildCurves(g, seg);
            ok = touchedPatchesAreDisks(toggled) && (!keepSplit || region.empty() || patchesOver(seg, region) >= 2);
            if (!ok) {
              undo();
              rebuildCurves(g, seg);
              continue;
            }
          }
          if (ok) {
            ++moved;
          } else {
            undo();
          }
        }
    if (moved == 0) break;
    total += moved;
  }
  if (total == 0) return 0;
  rebuildCurves(g, seg);
  return keepCutsIfAllDisks(g, seg, original) ? total : 0;
}

uint32_t absorbCutSlivers(const EdgeGraph& g, Segmentation& seg, double minAngle, const std::vector<uint32_t>& region) {
  constexpr size_t kSliverFaces = 4;  // patches this small are tried
  const std::vector<EdgeKind> original = seg.edgeKind;
  std::vector<uint32_t> ids;
  if (region.empty()) {
    for (uint32_t p = 0; p < seg.patches.size(); ++p) ids.push_back(p);
  } else {
    for (uint32_t f : region) ids.push_back(seg.facePatch[f]);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
  // the faces of the small patches with a corner below minAngle between two cuts
  std::vector<std::vector<uint32_t>> slivers;
  for (uint32_t p : ids) {
    const auto& faces = seg.patches[p];
    if (faces.size() > kSliverFaces) continue;
    std::vector<std::pair<uint32_t, double>> wedge;  // (vertex, 3D angle inside p)
    for (uint32_t f : faces)
      for (int c = 0; c < 3; ++c) {
        auto it = std::find_if(wedge.begin(), wedge.end(), [&](const auto& w) { return w.first == g.faces[f][c]; });
        if (it == wedge.end()) wedge.push_back({g.faces[f][c], g.cornerAngle(f, c)});
        else it->second += g.cornerAngle(f, c);
      }
    bool sharp = false;
    for (const auto& [v, a] : wedge) {
      if (a >= minAngle) continue;
      bool onlyCuts = true, onCurve = false;
      for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
        const EdgeKind kd = seg.edgeKind[g.vertexEdgeIds[k]];
        onCurve = onCurve || kd != EdgeKind::None;
        onlyCuts = onlyCuts && (kd == EdgeKind::None || kd == EdgeKind::Cut);
      }
      sharp = sharp || (onCurve && onlyCuts);
    }
    if (sharp) slivers.push_back(faces);
  }
  uint32_t absorbed = 0;
  for (const auto& faces : slivers) {
    // the border cut edges, longest first: the sliver joins the patch across one of them
    std::vector<uint32_t> border;
    const uint32_t p = seg.facePatch[faces[0]];
    if (seg.patches[p].size() != faces.size()) continue;  // an earlier move took it in
    for (uint32_t f : faces)
      for (uint32_t e : g.faceEdges[f])
        if (seg.edgeKind[e] == EdgeKind::Cut) border.push_back(e);
    sortLongestFirst(g, border);
    for (uint32_t e0 : border) {
      const uint32_t f0 = g.edgeFaces[e0][0], f1 = g.edgeFaces[e0][1];
      if (f0 == kNone || f1 == kNone || (seg.facePatch[f0] != p && seg.facePatch[f1] != p)) continue;
      const uint32_t q = seg.facePatch[f0] == p ? seg.facePatch[f1] : seg.facePatch[f0];
      if (q == p) continue;
      const std::vector<EdgeKind> before = seg.edgeKind;
      // every cut between the two goes, then the cut branches left dangling
      std::vector<uint32_t> ends;
      for (uint32_t f : seg.patches[p])
        for (uint32_t e : g.faceEdges[f]) {
          const uint32_t a = g.edgeFaces[e][0], b = g.edgeFaces[e][1];
          if (seg.edgeKind[e] != EdgeKind::Cut || a == kNone || b == kNone) continue;
          if (seg.facePatch[a] == q || seg.facePatch[b] == q) {
            seg.edgeKind[e] = EdgeKind::None;
            ends.push_back(g.edgeVerts[e][0]);
            ends.push_back(g.edgeVerts[e][1]);
          }
        }
      const bool ok = pruneDanglingCuts(g, seg, ends, std::ptrdiff_t(g.edgeCount()), [&](uint32_t e) { seg.edgeKind[e] = EdgeKind::None; });
      if (ok) {
        rebuildCurves(g, seg);
        if (keepCutsIfAllDisks(g, seg, before)) {
          ++absorbed;
          break;
        }
      } else {
        seg.edgeKind = before;
      }
    }
  }
  if (absorbed == 0) {
    if (seg.edgeKind != original) {
      seg.edgeKind = original;
      rebuildCurves(g, seg);
    }
    return 0;
  }
  seg.cutEdgeCount = 0;
  for (EdgeKind kd : seg.edgeKind) seg.cutEdgeCount += kd == EdgeKind::Cut;
  return absorbed;
}

uint32_t moveNarrowCutWedges(const EdgeGraph& g, Segmentation& seg, double minAngle, const std::vector<uint32_t>& region) {
  std::vector<uint32_t> verts;
  if (region.empty()) {
    for (uint32_t v = 0; v < g.vertexCount; ++v) verts.push_back(v);
  } else {
    for (uint32_t f : region)
      for (uint32_t v : g.faces[f]) verts.push_back(v);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  }
  const auto isCurve = [&](uint32_t e) { return seg.isCurveEdge(e); };
  WedgeScratch scratch, groups;  // groups: v's wedges while scratch measures after a move
  uint32_t moved = 0;
  for (uint32_t v : verts) {
    bool cut = false;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
      cut = cut || seg.edgeKind[g.vertexEdgeIds[k]] == EdgeKind::Cut;
    if (!cut || !groupWedges(g, v, isCurve, groups)) continue;
    for (uint32_t root = 0; root < groups.star.size(); ++root) {
      if (wedgeRoot(groups, root) != root || groups.sum[root] >= minAngle) continue;
      std::vector<uint32_t> faces;
      for (uint32_t i = 0; i < groups.star.size(); ++i)
        if (wedgeRoot(groups, i) == root) faces.push_back(groups.star[i]);
      const uint32_t p = seg.facePatch[faces[0]];
      // its cut sides at v with another patch across, longest first
      std::vector<uint32_t> sides;
      for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
        const uint32_t e = g.vertexEdgeIds[k];
        if (seg.edgeKind[e] != EdgeKind::Cut || g.isBoundary(e)) continue;
        const uint32_t a = g.edgeFaces[e][0], b = g.edgeFaces[e][1];
        const bool inA = std::find(faces.begin(), faces.end(), a) != faces.end();
        const bool inB = std::find(faces.begin(), faces.end(), b) != faces.end();
        if (inA != inB && seg.facePatch[inA ? b : a] != p) sides.push_back(e);
      }
      sortLongestFirst(g, sides);
      const uint32_t movedBefore = moved;
      for (uint32_t e : sides) {
        const std::vector<EdgeKind> before = seg.edgeKind;
        // the vertices whose wedges change, and how narrow they were
        std::vector<std::pair<uint32_t, double>> watch{{v, 0.0}};
        seg.edgeKind[e] = EdgeKind::None;
        watch.push_back({g.otherVertex(e, v), 0.0});
        for (uint32_t f : faces)
          for (uint32_t x : g.faceEdges[f]) {
            if (g.edgeVerts[x][0] == v || g.edgeVerts[x][1] == v || seg.edgeKind[x] != EdgeKind::None) continue;
            const uint32_t o = g.edgeFaces[x][0] == f ? g.edgeFaces[x][1] : g.edgeFaces[x][0];
            if (o == kNone || seg.facePatch[o] != p || std::find(faces.begin(), faces.end(), o) != faces.end()) continue;
            seg.edgeKind[x] = EdgeKind::Cut;
            for (uint32_t w : g.edgeVerts[x]) watch.push_back({w, 0.0});
          }
        // a cut left with no other curve at v (or at e's far end) goes back to where it meets one
        if (!pruneDanglingCuts(g, seg, {v, g.otherVertex(e, v)}, std::ptrdiff_t(g.edgeCount()), [&](uint32_t x) { seg.edgeKind[x] = EdgeKind::None; })) {
          seg.edgeKind = before;
          continue;
        }
        std::sort(watch.begin(), watch.end());
        watch.erase(std::unique(watch.begin(), watch.end(), [](const auto& a, const auto& b) { return a.first == b.first; }), watch.end());
        const auto wasCurve = [&](uint32_t x) { return before[x] != EdgeKind::None; };
        for (auto& [w, a] : watch) a = smallestWedge(g, w, wasCurve, scratch);  // as they were
        rebuildCurves(g, seg);
        bool ok = keepCutsIfAllDisks(g, seg, before);
        for (const auto& [w, a] : watch) {
          const double now = smallestWedge(g, w, isCurve, scratch);
          ok = ok && now >= std::min(minAngle, a) && (w != v || now > a);
        }
        if (ok) {
          ++moved;
          break;
        }
        if (seg.edgeKind != before) {
          seg.edgeKind = before;
          rebuildCurves(g, seg);
        }
      }
      if (moved > movedBefore) break;  // the wedges at v changed: the next vertex
    }
  }
  seg.cutEdgeCount = 0;  // keepCutsIfAllDisks counted a move that was then undone
  for (EdgeKind kd : seg.edgeKind) seg.cutEdgeCount += kd == EdgeKind::Cut;
  return moved;
}

}  // namespace conformesh::features
