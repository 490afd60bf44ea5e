#include "features/segmentation.h"
#include "core/constants.h"
#include "features/creases.h"
#include "features/close_junctions.h"
#include "features/cut_junctions.h"
#include "features/merge_cut_patches.h"
#include "features/patch_width.h"
#include "features/wedges.h"
#include "core/detmath.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <string>

namespace conformesh::features {
namespace {

// Geodesic Voronoi partition of the face set `region` (Dijkstra on the dual graph, centroid
// distances, never crossing a curve edge) with farthest-point seeds, one seed at a time: the
// partition with k seeds is the one with k - 1 updated by the k-th seed's Dijkstra (only faces
// closer to it change), so trying k = 2, 3, ... costs one partition, not one per k. `local` maps
// input face -> index in region (kNone outside); `label` is in [0, seeds) per region face.
struct VoronoiSeeds {
  const EdgeGraph& g;
  const std::vector<uint8_t>& mask;
  const std::vector<uint32_t>& region;
  const std::vector<uint32_t>& local;
  std::vector<double> dist;
  std::vector<uint32_t> label;
  std::vector<Vec3> centroid;
  uint32_t seeds = 0;
  uint32_t next = kNone;  // the next seed: the face farthest from the seeds so far
  std::vector<uint32_t> first;  // seeds taken in this order before the farthest points
  std::vector<uint32_t> seedFaces;  // the seeds run, in label order

  VoronoiSeeds(const EdgeGraph& g_, const std::vector<uint8_t>& m, const std::vector<uint32_t>& r,
               const std::vector<uint32_t>& l, std::vector<uint32_t> firstSeeds = {})
      : g(g_), mask(m), region(r), local(l), dist(r.size(), INFINITY), label(r.size(), kNone), centroid(r.size()),
        first(std::move(firstSeeds)) {
    for (uint32_t i = 0; i < region.size(); ++i) centroid[i] = g.faceCentroid(region[i]);
    if (region.empty()) return;
    if (!first.empty()) {
      next = first[0];
      return;
    }
    // first seed: farthest from region[0]
    run(0, 0);
    next = uint32_t(std::max_element(dist.begin(), dist.end(),
                                     [](double a, double b) {
                                       return (std::isinf(a) ? -1.0 : a) < (std::isinf(b) ? -1.0 : b);
                                     }) - dist.begin());
    std::fill(dist.begin(), dist.end(), INFINITY);
    std::fill(label.begin(), label.end(), kNone);
    seedFaces.clear();
  }

  // incremental multi-source Dijkstra: only faces closer to the new seed change
  void run(uint32_t seed, uint32_t lab) {
    if (lab == seedFaces.size()) seedFaces.push_back(seed);
    using Item = std::pair<double, uint32_t>;
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
  }

  // Add seeds until there are k (fewer when every face is a seed's or unreachable).
  void growTo(uint32_t k) {
    while (seeds < k && next != kNone) {
      run(next, seeds++);
      if (seeds < first.size()) {
        next = first[seeds];
        continue;
      }
      double best = -1;
      next = kNone;
      for (uint32_t i = 0; i < dist.size(); ++i)
        if (dist[i] > best) best = dist[i], next = i;
      if (best <= 0) next = kNone;
    }
  }
};

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

  // The parts of a partition, one per label. A tie in the distances can leave a cell in pieces
  // (symmetric seeds on a regular grid do): a piece without its cell's seed joins the cell of a
  // face beside it, so every part is connected.
  std::vector<std::vector<uint32_t>> groups(const std::vector<uint32_t>& region, std::vector<uint32_t>& label,
                                            const std::vector<uint32_t>& seedFaces) {
    std::vector<uint32_t> piece(region.size(), kNone), stack, members;
    auto neighbours = [&](uint32_t i, auto&& visit) {
      for (uint32_t e : g.faceEdges[region[i]]) {
        if (mask[e]) continue;
        const uint32_t o = g.edgeFaces[e][0] == region[i] ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
        const uint32_t j = o == kNone ? kNone : local[o];
        if (j != kNone) visit(j);
      }
    };
    // the seeds' pieces first: their faces keep their labels
    uint32_t pieces = 0;
    for (uint32_t s0 : seedFaces) {
      if (piece[s0] != kNone) continue;
      piece[s0] = pieces;
      stack.push_back(s0);
      while (!stack.empty()) {
        const uint32_t i = stack.back();
        stack.pop_back();
        neighbours(i, [&](uint32_t j) {
          if (piece[j] == kNone && label[j] == label[s0]) piece[j] = pieces, stack.push_back(j);
        });
      }
      ++pieces;
    }
    // every other piece takes the label of a seed's piece beside it (passes until none is left)
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t i0 = 0; i0 < region.size(); ++i0) {
        if (piece[i0] != kNone || label[i0] == kNone) continue;
        uint32_t to = kNone;
        members.assign(1, i0);
        piece[i0] = pieces;  // marks the stray piece while it is gathered
        for (size_t k = 0; k < members.size(); ++k)
          neighbours(members[k], [&](uint32_t j) {
            if (label[j] == label[i0] && piece[j] == kNone) piece[j] = pieces, members.push_back(j);
            else if (piece[j] != kNone && piece[j] < pieces && to == kNone) to = j;
          });
        for (uint32_t m : members) piece[m] = to == kNone ? kNone : piece[to];
        if (to == kNone) continue;  // no seed's piece beside it yet
        for (uint32_t m : members) label[m] = label[to];
        changed = true;
      }
    }
    std::vector<std::vector<uint32_t>> out(seedFaces.size());
    for (uint32_t i = 0; i < region.size(); ++i)
      if (label[i] != kNone && label[i] < out.size()) out[label[i]].push_back(region[i]);
    out.erase(std::remove_if(out.begin(), out.end(), [](const auto& v) { return v.empty(); }), out.end());
    return out;
  }

  // Two seeds (region-local face indices) that part a region that is not a disk where farthest
  // points often do not; `pm` is the region extracted with its loops, `local` set. With two or
  // more border loops: faces on opposite sides of the shortest loop, so the cells' border crosses
  // that loop twice and joins it to the others (a cell that keeps a whole loop inside is cut
  // again, one loop fewer each time). Pinched (touching itself at a vertex): a face in each of
  // the first pinch's wedges, so no cell keeps both. Empty otherwise (a closed region: the
  // farthest points do).
  std::vector<uint32_t> topologySeeds(const PatchMesh& pm) const {
    const auto& T = pm.mesh.triangles;
    if (pm.boundaryLoops.size() >= 2) {
      auto length = [&](const PatchMesh::BoundaryHalfedge& h) {
        return norm(g.positions[pm.vertexInput[T[3 * h.face + (h.corner + 1) % 3]]] -
                    g.positions[pm.vertexInput[T[3 * h.face + h.corner]]]);
      };
      std::vector<double> loopLength(pm.boundaryLoops.size(), 0.0);
      size_t shortest = 0;
      for (size_t l = 0; l < loopLength.size(); ++l) {
        for (const auto& h : pm.boundaryLoops[l]) loopLength[l] += length(h);
        if (loopLength[l] < loopLength[shortest]) shortest = l;
      }
      const auto& loop = pm.boundaryLoops[shortest];
      size_t half = 0;
      for (double run = 0; half + 1 < loop.size() && run < 0.5 * loopLength[shortest]; ++half) run += length(loop[half]);
      const uint32_t a = local[pm.faceInput[loop[0].face]], b = local[pm.faceInput[loop[half].face]];
      return a == b ? std::vector<uint32_t>{} : std::vector<uint32_t>{a, b};
    }
    if (!pm.pinched) return {};
    // the input vertex of least index with two wedges (sub-mesh vertices), a face at each
    std::vector<uint32_t> faceAt(pm.vertexInput.size(), kNone);
    for (uint32_t t = 0; t < pm.faceInput.size(); ++t)
      for (int c = 0; c < 3; ++c)
        if (faceAt[T[3 * t + c]] == kNone) faceAt[T[3 * t + c]] = local[pm.faceInput[t]];
    std::vector<std::pair<uint32_t, uint32_t>> wedges;  // (input vertex, sub-mesh vertex)
    for (uint32_t w = 0; w < pm.vertexInput.size(); ++w) wedges.push_back({pm.vertexInput[w], w});
    std::sort(wedges.begin(), wedges.end());
    for (size_t i = 0; i + 1 < wedges.size(); ++i)
      if (wedges[i].first == wedges[i + 1].first && faceAt[wedges[i].second] != faceAt[wedges[i + 1].second])
        return {faceAt[wedges[i].second], faceAt[wedges[i + 1].second]};
    return {};
  }

  // Partition `region` into parts by k = minK..maxK geodesic Voronoi cells (seeds: the topology
  // seeds of `pm`, the region extracted, when given; then farthest points); the first k whose
  // parts are all disks wins, else the k = maxK partition is kept and its non-disk parts are
  // returned in `todo`.
  void partition(const std::vector<uint32_t>& region, uint32_t minK, uint32_t maxK, const PatchMesh* pm,
                 std::vector<std::vector<uint32_t>>& done, std::vector<std::vector<uint32_t>>& todo,
                 const std::vector<uint32_t>& seedFaces = {}) {
    for (uint32_t i = 0; i < region.size(); ++i) local[region[i]] = i;
    std::vector<uint32_t> first = pm ? topologySeeds(*pm) : std::vector<uint32_t>{};
    if (!pm) {
      for (uint32_t f : seedFaces)
        if (local[f] != kNone && std::find(first.begin(), first.end(), local[f]) == first.end()) first.push_back(local[f]);
      if (first.size() < 2) first.clear();
    }
    maxK = std::min<uint32_t>(maxK, uint32_t(region.size()));
    std::vector<uint32_t> label, cut;
    std::vector<std::vector<uint32_t>> parts;
    std::vector<uint8_t> disk;
    // the cuts tried are undone: the mask it sees stays
    VoronoiSeeds voronoi(g, mask, region, local, std::move(first));
    for (uint32_t k = std::min(minK, maxK); k <= maxK; ++k) {
      voronoi.growTo(k);
      label = voronoi.label;
      parts = groups(region, label, voronoi.seedFaces);
      cut = borders(region, label);
      for (uint32_t e : cut) mask[e] = 1;
      disk.clear();
      for (const auto& p : parts) disk.push_back(isDiskRegion(g, mask, p));
      if (std::count(disk.begin(), disk.end(), 1) == std::ptrdiff_t(parts.size()) || k == maxK) break;
      for (uint32_t e : cut) mask[e] = 0;
    }
    for (uint32_t f : region) local[f] = kNone;
    for (uint32_t e : cut) {
      seg.edgeKind[e] = EdgeKind::Cut;
      ++seg.cutEdgeCount;
    }
    for (size_t i = 0; i < parts.size(); ++i) (disk[i] ? done : todo).push_back(std::move(parts[i]));
  }

  // Cut `patch` until every part is a disk, two parts at a time; counts the parts into
  // patchCount. Only the parts that still need it are halved again: a part that is a disk stays
  // whole, where a partition into many cells at once cuts them too (docs/decisions/0027).
  void toDisks(const std::vector<uint32_t>& patch, uint32_t& patchCount) {
    std::vector<std::vector<uint32_t>> todo{patch}, done;
    while (!todo.empty()) {
      auto r = std::move(todo.back());
      todo.pop_back();
      const PatchMesh pm = extractPatch(g, mask, r, true);
      if (pm.isDisk()) {
        ++patchCount;
        continue;
      }
      partition(r, 2, 2, &pm, done, todo);
      if (done.empty() && todo.size() == 1 && todo.back().size() == r.size()) {
        // no cut came of it (never seen): the farthest points, up to eight cells
        todo.pop_back();
        partition(r, 2, 8, nullptr, done, todo);
        if (done.empty() && todo.size() == 1 && todo.back().size() == r.size())
          fail(Code::InternalError, Stage::Segment, "a region that is not a disk could not be cut");
      }
      patchCount += uint32_t(done.size());
      done.clear();
      if (patchCount + todo.size() > maxPatches)
        fail(Code::IterationLimit, Stage::Segment,
             "cutting patches into disks needs more than " + std::to_string(maxPatches) + " patches");
    }
  }
};

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
    const PatchExtents extents = patchExtents(g, seg);
    const std::vector<double>& area = extents.area;
    const std::vector<double>& perimeter = extents.perimeter;
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


}  // namespace

// Continue every dangling feature curve (a vertex with exactly one curve edge) along the
// straightest path of input edges until it meets a curve, so no patch contains a slit. A step
// onto another curve's dangling end that would make a wedge narrower than kNarrowCutWedge there
// (and narrower than the vertex had) is taken only when no other step is left (other curve
// vertices are left to improveCutJunctions): on a fan of needle faces the straightest edge can
// reach a curve's dangling end right beside its last edge, a hairpin (docs/decisions/0005).
void extendDanglingCurves(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& from) {
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
  std::vector<uint32_t> starts = from;
  if (from.empty())
    for (uint32_t v = 0; v < g.vertexCount; ++v) starts.push_back(v);
  for (const uint32_t v0 : starts) {
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
  if (innerCreases)
    for (uint32_t c = 0; c < curves.size(); ++c)
      if (isInnerCurve(c))
        for (uint32_t e : curves[c].edges) m[e] = 0;
  return m;
}

std::vector<double> featureWedgeAngles(const EdgeGraph& g, const Segmentation& seg) {
  std::vector<double> out(g.vertexCount, 2 * kPi);
  WedgeScratch scratch;
  auto separates = [&](uint32_t e) { return seg.edgeKind[e] == EdgeKind::Feature || seg.edgeKind[e] == EdgeKind::Boundary; };
  for (uint32_t v = 0; v < g.vertexCount; ++v) out[v] = smallestWedge(g, v, separates, scratch);
  return out;
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
  seg.angleBoundDeg = options.angleBoundDeg;
  seg.junctionScale = options.junctionScale;
  seg.innerCreases = options.innerCreases;
  seg.edgeKind.assign(g.edgeCount(), EdgeKind::None);
  if (options.detectCreases) {
    CreaseOptions co;
    co.featureAngleDeg = options.featureAngleDeg;
    co.minLength = options.minFeatureLength;
    co.outlierTipDeg = std::min(options.angleBoundDeg, kSliverTipDeg);
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
  if (!options.innerCreases) extendDanglingCurves(g, seg);
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
  // strips narrower than an output edge that only cuts border (features/merge_cut_patches.h)
  if (mergeCutPatches(g, seg, seg.junctionScale) > 0) rebuildCurves(g, seg);
  improveCutJunctions(g, seg, seg.junctionScale);
  mergeCloseJunctions(g, seg, kCloseJunctionFactor * seg.junctionScale);
  straightenCutEars(g, seg);
  absorbCutSlivers(g, seg, seg.angleBoundDeg * kPi / 180);
  moveNarrowCutWedges(g, seg, seg.angleBoundDeg * kPi / 180);
  if (progress && !progress(Stage::Segment, 1.0)) fail(Code::Cancelled, Stage::Segment, "cancelled");
  return seg;
}

uint32_t curveValence(const EdgeGraph& g, const Segmentation& seg, uint32_t v) {
  uint32_t n = 0;
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) n += seg.isCurveEdge(g.vertexEdgeIds[k]);
  return n;
}

void repairNewCuts(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& region, uint32_t through) {
  // the most of region one part may hold after a repair: less than all of it, and at most half
  // of what the cuts parted off the largest part back in it
  const size_t parted = region.size() - largestShare(seg, region);
  const size_t mostKept = region.size() - std::max<size_t>(1, (parted + 1) / 2);
  const auto valence = [&] { return through == kNone ? 0 : curveValence(g, seg, through); };
  const uint32_t cutValence = valence();
  const auto keepingSplit = [&](auto&& repair) {
    const std::vector<EdgeKind> before = seg.edgeKind;
    const uint32_t cutEdges = seg.cutEdgeCount, rerouted = seg.reroutedCutEnds;
    if (repair() > 0 && (largestShare(seg, region) > mostKept || valence() < cutValence)) {
      seg.edgeKind = before;
      seg.cutEdgeCount = cutEdges;
      seg.reroutedCutEnds = rerouted;
      rebuildCurves(g, seg);
    }
  };
  keepingSplit([&] { return improveCutJunctions(g, seg, seg.junctionScale, region); });
  keepingSplit([&] { return mergeCloseJunctions(g, seg, kCloseJunctionFactor * seg.junctionScale, region); });
  keepingSplit([&] { return straightenCutEars(g, seg, region, true); });
  keepingSplit([&] { return absorbCutSlivers(g, seg, seg.angleBoundDeg * kPi / 180, region); });
  keepingSplit([&] { return moveNarrowCutWedges(g, seg, seg.angleBoundDeg * kPi / 180, region); });
}

bool splitPatch(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t parts, const std::vector<uint32_t>& seeds) {
  if (p >= seg.patches.size() || seg.patches[p].size() < 2) return false;
  const std::vector<uint32_t> region = seg.patches[p];  // the new cuts and their ends lie in it
  const std::vector<EdgeKind> kinds = seg.edgeKind;
  const uint32_t cuts = seg.cutEdgeCount;
  std::vector<std::vector<uint32_t>> done, todo;
  // the farthest points first; when they leave the seeds in one part, the seeds themselves
  const auto together = [&] {
    for (const auto* parts : {&done, &todo})
      for (const auto& part : *parts)
        if (std::count_if(seeds.begin(), seeds.end(), [&](uint32_t f) { return std::find(part.begin(), part.end(), f) != part.end(); }) >= 2)
          return true;
    return false;
  };
  Cutter farthest(g, seg, 1u << 30);
  farthest.partition(region, std::max<uint32_t>(2, parts), 8, nullptr, done, todo);
  const bool seeded = seeds.size() >= 2 && together();
  if (seeded) {
    seg.edgeKind = kinds;
    seg.cutEdgeCount = cuts;
    done.clear();
    todo.clear();
  }
  Cutter apart(g, seg, 1u << 30);
  if (seeded) apart.partition(region, std::max<uint32_t>(2, parts), 8, nullptr, done, todo, seeds);
  Cutter& cutter = seeded ? apart : farthest;
  uint32_t count = 0;
  while (!todo.empty()) {
    auto r = std::move(todo.back());
    todo.pop_back();
    cutter.toDisks(r, count);
  }
  rebuildCurves(g, seg);
  repairNewCuts(g, seg, region);
  return true;
}

bool closeInnerCreases(const EdgeGraph& g, Segmentation& seg, uint32_t p) {
  if (!seg.innerCreases || p >= seg.patches.size()) return false;
  std::vector<uint32_t> tips;
  for (uint32_t c = 0; c < seg.curves.size(); ++c)
    if (seg.isInnerCurve(c) && seg.curves[c].patches[0] == p)
      for (const uint32_t v : {seg.curves[c].vertices.front(), seg.curves[c].vertices.back()}) tips.push_back(v);
  std::sort(tips.begin(), tips.end());
  tips.erase(std::unique(tips.begin(), tips.end()), tips.end());
  // the dangling ends (one curve edge): a junction of inner curves or an end on the border is none
  tips.erase(std::remove_if(tips.begin(), tips.end(), [&](uint32_t v) { return curveValence(g, seg, v) != 1; }), tips.end());
  if (tips.empty()) return false;
  const std::vector<uint32_t> region = seg.patches[p];
  extendDanglingCurves(g, seg, tips);
  rebuildCurves(g, seg);
  // the parts the continued creases closed off, cut into disks
  std::vector<uint32_t> partOf;
  for (const uint32_t f : region) partOf.push_back(seg.facePatch[f]);
  std::sort(partOf.begin(), partOf.end());
  partOf.erase(std::unique(partOf.begin(), partOf.end()), partOf.end());
  std::vector<std::vector<uint32_t>> parts;
  for (const uint32_t q : partOf) parts.push_back(seg.patches[q]);
  Cutter cutter(g, seg, 1u << 30);
  uint32_t count = 0;
  for (auto& part : parts) cutter.toDisks(part, count);
  rebuildCurves(g, seg);
  if (mergeCutPatches(g, seg, seg.junctionScale, region) > 0) rebuildCurves(g, seg);
  if (patchesOver(seg, region) >= 2) repairNewCuts(g, seg, region);
  return true;
}

}  // namespace conformesh::features
