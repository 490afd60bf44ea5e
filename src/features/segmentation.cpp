#include "features/segmentation.h"
#include "features/creases.h"
#include "core/detmath.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <string>

namespace conformesh::features {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Geodesic Voronoi partition of the face set `region` (Dijkstra on the dual graph, centroid
// distances, never crossing a curve edge) with k farthest-point seeds. `local` maps input face ->
// index in region (kNone outside). Returns a label in [0, k) per region face.
std::vector<uint32_t> voronoiPartition(const EdgeGraph& g, const std::vector<uint8_t>& mask,
                                       const std::vector<uint32_t>& region,
                                       const std::vector<uint32_t>& local, uint32_t k) {
  const uint32_t n = uint32_t(region.size());
  std::vector<double> dist(n, INFINITY);
  std::vector<uint32_t> label(n, kNone);
  std::vector<Vec3> centroid(n);
  for (uint32_t i = 0; i < n; ++i) centroid[i] = g.faceCentroid(region[i]);
  using Item = std::pair<double, uint32_t>;
  auto run = [&](uint32_t seed, uint32_t lab) {
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    dist[seed] = 0;
    label[seed] = lab;
    pq.push({0.0, seed});
    while (!pq.empty()) {
      auto [d, i] = pq.top();
      pq.pop();
      if (d > dist[i]) continue;
      uint32_t f = region[i];
      for (int c = 0; c < 3; ++c) {
        uint32_t e = g.faceEdges[f][c];
        if (mask[e]) continue;
        uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
        if (o == kNone) continue;
        uint32_t j = local[o];
        if (j == kNone) continue;
        double nd = d + norm(centroid[j] - centroid[i]);
        if (nd < dist[j]) {
          dist[j] = nd;
          label[j] = lab;
          pq.push({nd, j});
        }
      }
    }
  };
  // first seed: farthest from region[0]
  run(0, 0);
  uint32_t seed = uint32_t(std::max_element(dist.begin(), dist.end(),
                                            [](double a, double b) {
                                              return (std::isinf(a) ? -1.0 : a) < (std::isinf(b) ? -1.0 : b);
                                            }) - dist.begin());
  std::fill(dist.begin(), dist.end(), INFINITY);
  std::fill(label.begin(), label.end(), kNone);
  for (uint32_t s = 0; s < k; ++s) {
    run(seed, s);  // incremental multi-source Dijkstra: only faces closer to the new seed change
    double best = -1;
    uint32_t next = kNone;
    for (uint32_t i = 0; i < n; ++i)
      if (dist[i] > best) best = dist[i], next = i;
    if (next == kNone || best <= 0) break;
    seed = next;
  }
  return label;
}

struct Cutter {
  const EdgeGraph& g;
  Segmentation& seg;
  std::vector<uint8_t> mask;
  std::vector<uint32_t> local;
  uint32_t maxPatches;

  Cutter(const EdgeGraph& g_, Segmentation& s, uint32_t maxP)
      : g(g_), seg(s), mask(s.curveMask()), local(g_.faceCount, kNone), maxPatches(maxP) {}

  // Mark (value 1) or unmark (0) the borders between different labels of a partition.
  std::vector<uint32_t> borders(const std::vector<uint32_t>& region, const std::vector<uint32_t>& label) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < region.size(); ++i) {
      uint32_t f = region[i];
      for (int c = 0; c < 3; ++c) {
        uint32_t e = g.faceEdges[f][c];
        if (mask[e]) continue;
        uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
        if (o == kNone || local[o] == kNone || o < f) continue;
        if (label[local[o]] != label[i]) out.push_back(e);
      }
    }
    return out;
  }

  std::vector<std::vector<uint32_t>> groups(const std::vector<uint32_t>& region,
                                            const std::vector<uint32_t>& label, uint32_t k) {
    std::vector<std::vector<uint32_t>> out(k);
    for (uint32_t i = 0; i < region.size(); ++i)
      if (label[i] != kNone) out[label[i]].push_back(region[i]);
    out.erase(std::remove_if(out.begin(), out.end(), [](const auto& v) { return v.empty(); }), out.end());
    return out;
  }

  // Partition `region` into parts, trying k = minK.. up to 8 seeds; the first k whose parts are
  // all disks wins, else the k = 8 partition is kept and its non-disk parts are returned in `todo`.
  void partition(const std::vector<uint32_t>& region, uint32_t minK, std::vector<std::vector<uint32_t>>& done,
                 std::vector<std::vector<uint32_t>>& todo) {
    for (uint32_t i = 0; i < region.size(); ++i) local[region[i]] = i;
    const uint32_t maxK = std::min<uint32_t>(8, uint32_t(region.size()));
    std::vector<uint32_t> label, cut;
    std::vector<std::vector<uint32_t>> parts;
    for (uint32_t k = std::min(minK, maxK); k <= maxK; ++k) {
      label = voronoiPartition(g, mask, region, local, k);
      cut = borders(region, label);
      parts = groups(region, label, k);
      for (uint32_t e : cut) mask[e] = 1;
      bool all = true;
      for (const auto& p : parts)
        if (!extractPatch(g, mask, p, false).isDisk()) { all = false; break; }
      if (all || k == maxK) break;
      for (uint32_t e : cut) mask[e] = 0;
    }
    for (uint32_t f : region) local[f] = kNone;
    for (uint32_t e : cut) {
      seg.edgeKind[e] = EdgeKind::Cut;
      ++seg.cutEdgeCount;
    }
    for (auto& p : parts) {
      if (extractPatch(g, mask, p, false).isDisk()) done.push_back(std::move(p));
      else todo.push_back(std::move(p));
    }
  }

  // Cut `patch` until every part is a disk; counts the parts into patchCount.
  void toDisks(const std::vector<uint32_t>& patch, uint32_t& patchCount) {
    std::vector<std::vector<uint32_t>> todo{patch}, done;
    while (!todo.empty()) {
      auto r = std::move(todo.back());
      todo.pop_back();
      if (extractPatch(g, mask, r, false).isDisk()) {
        ++patchCount;
        continue;
      }
      partition(r, 2, done, todo);
      patchCount += uint32_t(done.size());
      done.clear();
      if (patchCount + todo.size() > maxPatches)
        fail(Code::IterationLimit, Stage::Segment,
             "cutting patches into disks needs more than " + std::to_string(maxPatches) + " patches");
    }
  }
};

struct WedgeScratch {
  std::vector<uint32_t> star, parent;
  std::vector<double> sum;
};

// The smallest wedge at v between edges for which separates(e) holds (the open boundary always
// separates): the sum of the face angles at v between two consecutive such edges, found by
// joining the faces of v's star across the other edges (union-find). 2π when no such edge
// touches v; the full angle sum at v when one does.
template <class Separates>
double smallestWedge(const EdgeGraph& g, uint32_t v, const Separates& separates, WedgeScratch& w) {
  bool touched = false;
  w.star.clear();
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (separates(e) || g.isBoundary(e)) touched = true;
    for (uint32_t f : g.edgeFaces[e])
      if (f != kNone) w.star.push_back(f);
  }
  if (!touched) return 2 * kPi;
  std::sort(w.star.begin(), w.star.end());
  w.star.erase(std::unique(w.star.begin(), w.star.end()), w.star.end());
  w.parent.resize(w.star.size());
  for (uint32_t i = 0; i < w.parent.size(); ++i) w.parent[i] = i;
  auto find = [&](uint32_t i) {
    while (w.parent[i] != i) i = w.parent[i] = w.parent[w.parent[i]];
    return i;
  };
  auto slot = [&](uint32_t f) { return uint32_t(std::lower_bound(w.star.begin(), w.star.end(), f) - w.star.begin()); };
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (separates(e) || g.isBoundary(e)) continue;
    w.parent[find(slot(g.edgeFaces[e][0]))] = find(slot(g.edgeFaces[e][1]));
  }
  w.sum.assign(w.star.size(), 0.0);
  for (uint32_t i = 0; i < w.star.size(); ++i) {
    const auto& fv = g.faces[w.star[i]];
    for (int c = 0; c < 3; ++c)
      if (fv[c] == v) w.sum[find(i)] += g.cornerAngle(w.star[i], c);
  }
  double m = 2 * kPi;
  for (uint32_t i = 0; i < w.star.size(); ++i)
    if (find(i) == i) m = std::min(m, w.sum[i]);
  return m;
}

// Patches: faces connected across edges that are not curve edges (seg.facePatch, seg.patches).
void floodPatches(const EdgeGraph& g, Segmentation& seg) {
  seg.facePatch.assign(g.faceCount, kNone);
  seg.patches.clear();
  std::vector<uint32_t> stack;
  for (uint32_t f0 = 0; f0 < g.faceCount; ++f0) {
    if (seg.facePatch[f0] != kNone) continue;
    uint32_t p = uint32_t(seg.patches.size());
    seg.patches.emplace_back();
    seg.facePatch[f0] = p;
    stack.push_back(f0);
    while (!stack.empty()) {
      uint32_t f = stack.back();
      stack.pop_back();
      seg.patches[p].push_back(f);
      for (uint32_t e : g.faceEdges[f]) {
        if (seg.isCurveEdge(e)) continue;
        uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
        if (o != kNone && seg.facePatch[o] == kNone) {
          seg.facePatch[o] = p;
          stack.push_back(o);
        }
      }
    }
  }
}

// Merge patches narrower than minWidth into a neighbour (FeatureOptions::minPatchWidth). Width:
// 2·area / perimeter, the width of a strip (a disk's radius, half a sliver triangle's height).
// Delaunay refinement meshes a strip of width w with boundary segments of about 2w (a longer one
// is encroached by the far side), so a strip narrower than half the smallest allowed edge is
// meshed below the sizing's floor, with thousands of samples along it and a graded band
// around it. Each narrow patch joins the neighbour across its longest border of droppable
// sharp edges (not user features, not the open boundary): the feature stays drawn by the
// strip's other border, within w of it. Narrowest first; passes until none merges (capped).
// Returns the number of merges.
uint32_t mergeNarrowPatches(const EdgeGraph& g, Segmentation& seg, double minWidth, const std::vector<uint8_t>& userEdge) {
  constexpr int kMaxPasses = 32;
  uint32_t merged = 0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    floodPatches(g, seg);
    const size_t np = seg.patches.size();
    if (np < 2) break;
    std::vector<double> area(np, 0.0), perimeter(np, 0.0);
    for (uint32_t f = 0; f < g.faceCount; ++f) area[seg.facePatch[f]] += g.faceArea(f);
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      const uint32_t f0 = g.edgeFaces[e][0], f1 = g.edgeFaces[e][1];
      const uint32_t p0 = seg.facePatch[f0], p1 = f1 == kNone ? kNone : seg.facePatch[f1];
      if (p0 == p1) continue;  // inside a patch (a slit counts for nothing)
      perimeter[p0] += g.edgeLength(e);
      if (p1 != kNone) perimeter[p1] += g.edgeLength(e);
    }
    std::vector<std::pair<double, uint32_t>> narrow;
    for (uint32_t p = 0; p < np; ++p)
      if (perimeter[p] > 0 && 2.0 * area[p] < minWidth * perimeter[p]) narrow.push_back({2.0 * area[p] / perimeter[p], p});
    if (narrow.empty()) break;
    std::sort(narrow.begin(), narrow.end());
    // droppable border length per (patch, neighbour)
    std::map<std::pair<uint32_t, uint32_t>, double> shared;
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      if (seg.edgeKind[e] != EdgeKind::Feature || userEdge[e] || g.isBoundary(e)) continue;
      const uint32_t p0 = seg.facePatch[g.edgeFaces[e][0]], p1 = seg.facePatch[g.edgeFaces[e][1]];
      if (p0 == p1) continue;
      shared[{p0, p1}] += g.edgeLength(e);
      shared[{p1, p0}] += g.edgeLength(e);
    }
    // in one pass a patch either merges into another or receives merges, never both
    std::vector<uint8_t> receives(np, 0);
    std::vector<uint32_t> target(np, kNone);
    uint32_t mergedNow = 0;
    for (const auto& [width, p] : narrow) {
      if (receives[p]) continue;
      uint32_t best = kNone;
      double bestLen = 0;
      for (auto it = shared.lower_bound({p, 0}); it != shared.end() && it->first.first == p; ++it)
        if (target[it->first.second] == kNone && it->second > bestLen) best = it->first.second, bestLen = it->second;
      // The border left must still draw the feature, as a strip's other side does: an island
      // (all its border shared with one patch) would lose its feature altogether, and whether
      // a small closed feature stays is minFeatureLength's call, not this one's.
      if (best == kNone || perimeter[p] - bestLen < 0.5 * bestLen) continue;
      receives[best] = 1;
      target[p] = best;
      ++mergedNow;
    }
    if (mergedNow == 0) break;
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      if (seg.edgeKind[e] != EdgeKind::Feature || userEdge[e] || g.isBoundary(e)) continue;
      const uint32_t p0 = seg.facePatch[g.edgeFaces[e][0]], p1 = seg.facePatch[g.edgeFaces[e][1]];
      if ((target[p0] == p1 && p1 != kNone) || (target[p1] == p0 && p0 != kNone)) {
        seg.edgeKind[e] = EdgeKind::None;
        --seg.sharpEdgeCount;
        ++seg.droppedFeatureEdges;
      }
    }
    merged += mergedNow;
  }
  return merged;
}

// A cut meeting a curve at a wedge narrower than this makes a corner no mesh can fix (cuts are
// ours, not features, so such a corner is not exempt); straightenCutEars and the walks of
// extendDanglingCurves avoid them.
constexpr double kNarrowCutWedge = 45.0 * kPi / 180.0;

}  // namespace

// Continue every dangling feature curve (a vertex with exactly one curve edge) along the
// straightest path of input edges until it meets a curve, so no patch contains a slit. A step
// onto another curve's dangling end that would make a wedge narrower than kNarrowCutWedge there
// (and narrower than the vertex had) is taken only when no other step is left (other curve
// vertices are left to improveCutJunctions): on a fan of needle faces the straightest edge can
// reach a curve's dangling end right beside its last edge, a hairpin (docs/decisions/0005).
void extendDanglingCurves(const EdgeGraph& g, Segmentation& seg) {
  std::vector<uint32_t> valence(g.vertexCount, 0);
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (seg.isCurveEdge(e)) ++valence[g.edgeVerts[e][0]], ++valence[g.edgeVerts[e][1]];
  std::vector<uint32_t> visitedStamp(g.vertexCount, kNone);
  WedgeScratch scratch;
  // would stepping along e onto the curve vertex w make a narrow wedge there?
  auto narrowArrival = [&](uint32_t e, uint32_t w) {
    const double before = smallestWedge(g, w, [&](uint32_t x) { return seg.isCurveEdge(x); }, scratch);
    const double after = smallestWedge(g, w, [&](uint32_t x) { return x == e || seg.isCurveEdge(x); }, scratch);
    return after < kNarrowCutWedge && after < before;
  };
  for (uint32_t v0 = 0; v0 < g.vertexCount; ++v0) {
    if (valence[v0] != 1) continue;
    uint32_t ein = kNone;
    for (uint32_t k = g.vertexEdgeStart[v0]; k < g.vertexEdgeStart[v0 + 1]; ++k)
      if (seg.isCurveEdge(g.vertexEdgeIds[k])) ein = g.vertexEdgeIds[k];
    uint32_t prev = g.otherVertex(ein, v0), cur = v0;
    visitedStamp[cur] = v0;
    for (uint32_t step = 0; step < g.vertexCount; ++step) {
      Vec3 dir = g.positions[cur] - g.positions[prev];
      double best = -INFINITY, bestNarrow = -INFINITY;
      uint32_t be = kNone, beNarrow = kNone;
      for (uint32_t k = g.vertexEdgeStart[cur]; k < g.vertexEdgeStart[cur + 1]; ++k) {
        uint32_t e = g.vertexEdgeIds[k];
        if (seg.isCurveEdge(e)) continue;
        uint32_t w = g.otherVertex(e, cur);
        if (w == prev || visitedStamp[w] == v0) continue;
        Vec3 d = g.positions[w] - g.positions[cur];
        double nd = norm(d) * norm(dir);
        double c = nd > 0 ? dot(d, dir) / nd : -1.0;
        if (c > best && valence[w] == 1 && narrowArrival(e, w)) {
          if (c > bestNarrow) bestNarrow = c, beNarrow = e;
        } else if (c > best) {
          best = c, be = e;
        }
      }
      if (be == kNone) be = beNarrow;
      if (be == kNone) break;
      uint32_t w = g.otherVertex(be, cur);
      seg.edgeKind[be] = EdgeKind::Cut;
      ++seg.cutEdgeCount;
      ++valence[cur];
      bool stop = valence[w] > 0;
      ++valence[w];
      visitedStamp[w] = v0;
      if (stop) break;
      prev = cur;
      cur = w;
    }
  }
}

std::vector<uint8_t> Segmentation::curveMask() const {
  std::vector<uint8_t> m(edgeKind.size());
  for (size_t e = 0; e < m.size(); ++e) m[e] = edgeKind[e] != EdgeKind::None;
  return m;
}

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

}  // namespace

// The faces of patches a and b (as they were) regrouped across the edges that are not curves now:
// exactly two groups, each a disk.
bool splitsIntoTwoDisks(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint8_t>& mask,
                        const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
  std::vector<uint32_t> faces(a);
  faces.insert(faces.end(), b.begin(), b.end());
  std::sort(faces.begin(), faces.end());
  std::vector<uint32_t> label(faces.size(), kNone), stack;
  auto slot = [&](uint32_t f) {
    auto it = std::lower_bound(faces.begin(), faces.end(), f);
    return it != faces.end() && *it == f ? uint32_t(it - faces.begin()) : kNone;
  };
  std::vector<std::vector<uint32_t>> groups;
  for (uint32_t i0 = 0; i0 < faces.size(); ++i0) {
    if (label[i0] != kNone) continue;
    if (groups.size() == 2) return false;
    label[i0] = uint32_t(groups.size());
    groups.emplace_back();
    stack.push_back(i0);
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      groups.back().push_back(faces[i]);
      for (uint32_t e : g.faceEdges[faces[i]]) {
        if (seg.isCurveEdge(e)) continue;
        const uint32_t o = g.edgeFaces[e][0] == faces[i] ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
        const uint32_t j = o == kNone ? kNone : slot(o);
        if (j != kNone && label[j] == kNone) {
          label[j] = label[i];
          stack.push_back(j);
        }
      }
    }
  }
  if (groups.size() != 2) return false;
  for (const auto& gr : groups)
    if (!extractPatch(g, mask, gr, false).isDisk()) return false;
  return true;
}

namespace {
// Whether the patches `ids` of seg (its curves rebuilt) are all disks.
bool patchesAreDisks(const EdgeGraph& g, const Segmentation& seg, const std::vector<uint32_t>& ids) {
  const std::vector<uint8_t> mask = seg.curveMask();
  for (const uint32_t p : ids)
    if (!extractPatch(g, mask, seg.patches[p], false).isDisk()) return false;
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
          old = std::min(old, angleBetween(d0, pointAlong(g, other, l) - g.positions[v]));
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
            if (side->size() > 1) now = std::min(now, angleBetween(dn, pointAlong(g, *side, l) - g.positions[x]));
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
          commit = splitsIntoTwoDisks(g, seg, mask, seg.patches[A], seg.patches[B]);
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

uint32_t straightenCutEars(const EdgeGraph& g, Segmentation& seg) {
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
  uint32_t total = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    uint32_t moved = 0;
    for (uint32_t f0 = 0; f0 < g.faceCount; ++f0)
      for (int c0 = 0; c0 < 3; ++c0)
        for (int side = 0; side < 2; ++side) {
          // the wedge at v from the cut edge v-a, turning away from it face by face until the
          // next curve edge v-c; rim: a, ..., c (the far vertices of the wedge's faces)
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
          for (uint32_t x : rim) {
            while (ok && valence(x) == 1) {
              uint32_t only = kNone;
              for (uint32_t k = g.vertexEdgeStart[x]; k < g.vertexEdgeStart[x + 1]; ++k)
                if (seg.isCurveEdge(g.vertexEdgeIds[k])) only = g.vertexEdgeIds[k];
              if (seg.edgeKind[only] != EdgeKind::Cut || toggled.size() > kMaxPrune) {
                ok = false;
                break;
              }
              toggle(only);
              x = g.otherVertex(only, x);
            }
          }
          ok = ok && wedgeAround(v, rim) > before + kGain;
          // a move that took an old cut off the rim or pruned a branch regroups faces of more
          // than two patches: it is kept only when every patch it touches stays a disk
          // (checked at once, so that one such move cannot undo all the others at the end)
          const bool regroups = oldCutOnRim || toggled.size() > size_t(1 + int(cutB)) + rimEdges.size();
          if (ok && regroups) {
            rebuildCurves(g, seg);
            ok = touchedPatchesAreDisks(toggled);
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

std::vector<double> featureWedgeAngles(const EdgeGraph& g, const Segmentation& seg) {
  std::vector<double> out(g.vertexCount, 2 * kPi);
  WedgeScratch scratch;
  auto separates = [&](uint32_t e) { return seg.edgeKind[e] == EdgeKind::Feature || seg.edgeKind[e] == EdgeKind::Boundary; };
  for (uint32_t v = 0; v < g.vertexCount; ++v) out[v] = smallestWedge(g, v, separates, scratch);
  return out;
}

void rebuildCurves(const EdgeGraph& g, Segmentation& seg) {
  const double turnLimit = seg.cornerTurnDeg * kPi / 180.0;
  std::vector<uint32_t> valence(g.vertexCount, 0);
  std::vector<std::array<uint32_t, 2>> twoEdges(g.vertexCount, {kNone, kNone});
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    if (!seg.isCurveEdge(e)) continue;
    for (uint32_t v : g.edgeVerts[e]) {
      if (valence[v] < 2) twoEdges[v][valence[v]] = e;
      ++valence[v];
    }
  }
  seg.vertexCorner.assign(g.vertexCount, 0);
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    if (valence[v] == 0) continue;
    if (valence[v] != 2) {
      seg.vertexCorner[v] = 1;
      continue;
    }
    uint32_t e1 = twoEdges[v][0], e2 = twoEdges[v][1];
    if (seg.edgeKind[e1] != seg.edgeKind[e2]) {
      seg.vertexCorner[v] = 1;
      continue;
    }
    // a cut is ours and smooth: it has no corners of its own (the staircase of input edges it
    // follows would otherwise put a corner, and so a forced output vertex, at every other step)
    if (seg.edgeKind[e1] == EdgeKind::Cut) continue;
    Vec3 a = g.positions[v] - g.positions[g.otherVertex(e1, v)];
    Vec3 b = g.positions[g.otherVertex(e2, v)] - g.positions[v];
    if (angleBetween(a, b) > turnLimit) seg.vertexCorner[v] = 1;
  }
  seg.curves.clear();
  seg.edgeCurve.assign(g.edgeCount(), kNone);
  auto nextEdge = [&](uint32_t v, uint32_t e) {
    return twoEdges[v][0] == e ? twoEdges[v][1] : twoEdges[v][0];
  };
  auto trace = [&](uint32_t v, uint32_t e) {
    Curve c;
    c.kind = seg.edgeKind[e];
    c.vertices.push_back(v);
    for (uint32_t guard = 0; guard <= g.edgeCount(); ++guard) {
      seg.edgeCurve[e] = uint32_t(seg.curves.size());
      c.edges.push_back(e);
      c.length += g.edgeLength(e);
      v = g.otherVertex(e, v);
      c.vertices.push_back(v);
      if (seg.vertexCorner[v]) break;
      e = nextEdge(v, e);
    }
    seg.curves.push_back(std::move(c));
  };
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    if (!seg.vertexCorner[v]) continue;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
      uint32_t e = g.vertexEdgeIds[k];
      if (seg.isCurveEdge(e) && seg.edgeCurve[e] == kNone) trace(v, e);
    }
  }
  // closed loops without a corner: two artificial corners, at the start and half the length
  for (uint32_t e0 = 0; e0 < g.edgeCount(); ++e0) {
    if (!seg.isCurveEdge(e0) || seg.edgeCurve[e0] != kNone) continue;
    uint32_t v = g.edgeVerts[e0][0], e = e0;
    std::vector<uint32_t> verts{v};
    std::vector<double> arc{0.0};
    for (uint32_t guard = 0; guard <= g.edgeCount(); ++guard) {
      arc.push_back(arc.back() + g.edgeLength(e));
      v = g.otherVertex(e, v);
      if (v == verts[0]) break;
      verts.push_back(v);
      e = nextEdge(v, e);
    }
    uint32_t half = 1;
    for (uint32_t i = 1; i < verts.size(); ++i)
      if (std::abs(arc[i] - 0.5 * arc.back()) < std::abs(arc[half] - 0.5 * arc.back())) half = i;
    seg.vertexCorner[verts[0]] = 2;
    seg.vertexCorner[verts[half]] = 2;
    trace(verts[0], e0);
    uint32_t back = twoEdges[verts[0]][0] == e0 ? twoEdges[verts[0]][1] : twoEdges[verts[0]][0];
    if (seg.edgeCurve[back] == kNone) trace(verts[0], back);
  }
  floodPatches(g, seg);
  for (auto& c : seg.curves) {
    const auto& fs = g.edgeFaces[c.edges[0]];
    c.patches = {fs[0] == kNone ? kNone : seg.facePatch[fs[0]], fs[1] == kNone ? kNone : seg.facePatch[fs[1]]};
  }
}

Segmentation segment(const EdgeGraph& g, const FeatureOptions& options, const ProgressFn& progress) {
  if (!(options.featureAngleDeg >= 0 && options.featureAngleDeg <= 180))
    fail(Code::InvalidArgument, Stage::Segment, "featureAngle must be in [0, 180] degrees");
  if (!(options.cornerTurnDeg >= 0 && options.cornerTurnDeg <= 180))
    fail(Code::InvalidArgument, Stage::Segment, "cornerTurn must be in [0, 180] degrees");
  if (!(options.minPatchWidth >= 0 && options.minPatchWidth < INFINITY))
    fail(Code::InvalidArgument, Stage::Segment, "minPatchWidth must be finite and >= 0");
  Segmentation seg;
  seg.cornerTurnDeg = options.cornerTurnDeg;
  seg.junctionScale = options.junctionScale;
  seg.edgeKind.assign(g.edgeCount(), EdgeKind::None);
  if (options.detectCreases) {
    CreaseOptions co;
    co.featureAngleDeg = options.featureAngleDeg;
    co.minLength = options.minFeatureLength;
    const Creases creases = detectCreases(g, co);
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      if (g.isBoundary(e)) seg.edgeKind[e] = EdgeKind::Boundary;
      else if (creases.edge[e]) seg.edgeKind[e] = EdgeKind::Feature;
    }
    seg.sharpEdgeCount = creases.creaseEdges;
    seg.droppedFeatureEdges = creases.candidates - creases.creaseEdges;
  } else {
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (g.isBoundary(e)) seg.edgeKind[e] = EdgeKind::Boundary;
  }
  std::vector<uint8_t> userEdge(g.edgeCount(), 0);
  for (const auto& fe : options.featureEdges) {
    if (fe[0] >= g.vertexCount || fe[1] >= g.vertexCount)
      fail(Code::InvalidArgument, Stage::Segment, "user feature edge refers to a vertex out of range");
    uint32_t e = g.findEdge(fe[0], fe[1]);
    if (e == kNone)
      fail(Code::InvalidArgument, Stage::Segment,
           "user feature edge (" + std::to_string(fe[0]) + ", " + std::to_string(fe[1]) + ") is not a mesh edge");
    userEdge[e] = 1;
    if (seg.edgeKind[e] == EdgeKind::None) {
      seg.edgeKind[e] = EdgeKind::Feature;
      ++seg.sharpEdgeCount;
    }
  }
  if (options.minPatchWidth > 0) seg.mergedNarrowPatches = mergeNarrowPatches(g, seg, options.minPatchWidth, userEdge);
  if (progress && !progress(Stage::Segment, 0.2)) fail(Code::Cancelled, Stage::Segment, "cancelled");
  extendDanglingCurves(g, seg);
  rebuildCurves(g, seg);
  if (progress && !progress(Stage::Segment, 0.4)) fail(Code::Cancelled, Stage::Segment, "cancelled");
  Cutter cutter(g, seg, options.maxPatches);
  uint32_t patchCount = 0;
  auto patches = seg.patches;
  for (size_t p = 0; p < patches.size(); ++p) {
    cutter.toDisks(patches[p], patchCount);
    if (progress && !progress(Stage::Segment, 0.4 + 0.55 * double(p + 1) / double(patches.size())))
      fail(Code::Cancelled, Stage::Segment, "cancelled");
  }
  rebuildCurves(g, seg);
  improveCutJunctions(g, seg, seg.junctionScale);
  straightenCutEars(g, seg);
  if (progress && !progress(Stage::Segment, 1.0)) fail(Code::Cancelled, Stage::Segment, "cancelled");
  return seg;
}

bool splitPatch(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t parts) {
  if (p >= seg.patches.size() || seg.patches[p].size() < 2) return false;
  const std::vector<uint32_t> region = seg.patches[p];  // the new cuts and their ends lie in it
  Cutter cutter(g, seg, 1u << 30);
  std::vector<std::vector<uint32_t>> done, todo;
  cutter.partition(seg.patches[p], std::max<uint32_t>(2, parts), done, todo);
  uint32_t count = 0;
  while (!todo.empty()) {
    auto r = std::move(todo.back());
    todo.pop_back();
    cutter.toDisks(r, count);
  }
  rebuildCurves(g, seg);
  improveCutJunctions(g, seg, seg.junctionScale, region);
  straightenCutEars(g, seg);
  return true;
}

}  // namespace conformesh::features
