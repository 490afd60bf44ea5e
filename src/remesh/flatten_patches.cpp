#include "remesh/flatten_patches.h"
#include "core/constants.h"
#include "core/parallel_for.h"
#include "features/merge_cut_patches.h"
#include "features/sink_cuts.h"
#include "remesh/curve_samples.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <set>
#include <string>

namespace conformesh::pipeline {
namespace {

// Patches with fewer input faces are not split further. A single triangle always develops
// isometrically, so splitting down to small patches beats the round-disk fallback, whose
// distortion on a small curved patch leaves triangles below the bound (docs/decisions/0009).
constexpr size_t kMinSplitFaces = 2;

// A patch whose scale factor spreads more than this is cut in two through its most shrunk vertex
// (features/sink_cuts.h). Measured on armadillo: the refinement gives 1.2-1.4 times the sizing's
// count on patches spreading up to 4, and 5-12 times on those spreading 10-50 (it grades towards
// the sink as a quality mesh can, far slower than the planar size shrinks there).
constexpr double kSinkScaleRatio = 4.0;

// A sink nearer the patch's border than this many output edges (the sizing there) is not cut
// through: the border already holds the scale that close, and the cut would only shave off a
// strip narrower than two output edges, which the refinement grades into (docs/decisions/0007).
// man: 16 of its 38 sink cuts were 0.3-1.5 edges deep, each shaving 2-50 faces off one patch
// while its spread stayed at 7-10; armadillo's, elk's, face's and spot's were 5 or more deep
// (docs/decisions/0039).
constexpr double kSinkDepth = 2.0;

// When a patch's flattening fails, a vertex whose 3D angle is within this of 2π the wrong way is
// cut through (features/sink_cuts.h) rather than left inside a part of a split, which fails
// again for the same reason however small: a border vertex whose wedge exceeds 2π − kConeGap
// (with u = 0 on the border its planar angle stays near the 3D one: little room is left before
// the layout overlaps itself), an interior vertex whose angle sum is below it (a cone the flat
// map must open inside the patch: with a long border edge in its star, no u with the border's
// fixed keeps every triangle valid). man: a 299° vertex failed from 2,026 faces down to 8.
constexpr double kConeGap = 0.25 * kPi;

// Once every patch is flattened, the patches narrower than this many output edges (twice the
// area over the perimeter) are joined, two at a time, to a neighbour across the cuts between them
// (features/merge_cut_patches.h), and each joined patch is flattened: it stays unless it fails,
// asks for a split, spreads its scale past both kSinkScaleRatio and its parts' spread, or has a
// spike tip sharper than its parts' (its cuts then come back, with its parts' flattenings). The
// cuts the flattening makes (closing inner creases, sinks, spikes, splits) leave narrow parts
// beside older cuts that only add border and junctions (man: 79 patches, 26 of them under 60
// faces). The joined patches hold at most the input's faces together: one more flattening of the
// input at most (docs/decisions/0050).
constexpr double kJoinWidth = 3.0;

// Rounds of joining (a hard cap; a round with no join ends them): an undone join's cuts are
// never made plain again, so its narrow patch tries its next neighbour in the next round.
constexpr int kJoinRounds = 4;

// An interior vertex is a spike tip when its angle sum is below this many times the angle bound:
// a fan of that many triangles around a flat point has angles of 2π over that many there, the
// bound at the tip once lifted (by Θ/2π) when Θ is this many bounds.
constexpr double kSpikeTipFan = 6.0;

// The 3D angle sum at each vertex of a patch over the patch's faces.
std::vector<double> cornerWedgeAngles(const F::PatchMesh& pm) {
  std::vector<double> a(pm.vertexInput.size(), 0.0);
  const auto& P = pm.mesh.positions;
  for (size_t f = 0; f < pm.faceInput.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      uint32_t v[3] = {pm.mesh.triangles[3 * f + c], pm.mesh.triangles[3 * f + (c + 1) % 3],
                       pm.mesh.triangles[3 * f + (c + 2) % 3]};
      const Vec3 p0 = vec3At(P, v[0]), p1 = vec3At(P, v[1]), p2 = vec3At(P, v[2]);
      a[v[0]] += F::angleBetween(p1 - p0, p2 - p0);
    }
  return a;
}

// Corners for the corner-preserving boundary condition (the fallback when the free boundary
// overlaps itself): boundary wedges at curve corners whose 3D angle differs from π by more than
// 10°, each with its own 3D angle as target; the flow spreads the rest of the boundary turning
// (2π − Σ(π − α)) along the sides by arc length, so the sides bend instead of the corners.
std::vector<std::pair<uint32_t, double>> boundaryCorners(const F::Segmentation& seg, const F::PatchMesh& pm) {
  std::vector<double> angle = cornerWedgeAngles(pm);
  std::vector<uint8_t> onBoundary(pm.vertexInput.size(), 0);
  for (const auto& h : pm.boundaryLoops[0]) onBoundary[pm.mesh.triangles[3 * h.face + h.corner]] = 1;
  std::vector<std::pair<uint32_t, double>> out;
  for (uint32_t v = 0; v < pm.vertexInput.size(); ++v) {
    if (!onBoundary[v] || !seg.vertexCorner[pm.vertexInput[v]]) continue;
    if (std::abs(angle[v] - kPi) < 10.0 * kPi / 180.0) continue;
    out.push_back({v, std::clamp(angle[v], 1e-3, 2 * kPi - 1e-3)});
  }
  return out;
}

// The boundary conditions in the order a patch tries them: opt.boundary, then the others in
// the order Free, Corners, Circle.
std::vector<BoundaryCondition> conditionOrder(BoundaryCondition first) {
  std::vector<BoundaryCondition> order = {first};
  for (BoundaryCondition bc : {BoundaryCondition::Free, BoundaryCondition::Corners, BoundaryCondition::Circle})
    if (bc != first) order.push_back(bc);
  return order;
}

const char* conditionName(BoundaryCondition bc) {
  return bc == BoundaryCondition::Free ? "free" : bc == BoundaryCondition::Corners ? "corner-preserving" : "round (circle)";
}

// One patch's flattening, made apart from the others (on any thread; it reads the surface only).
// The patch is split instead when its first boundary condition fails or its scale factors spread
// too far, but whether a split is made depends on the segmentation, which the splits change: that
// is decided in patch order by flattenPatches, and a split patch's flattening is dropped.
struct Flattening {
  std::unique_ptr<PatchWork> w;
  std::exception_ptr error;  // thrown at the patch's turn, as a serial loop would
  std::vector<std::pair<uint32_t, double>> corners;  // the corner-preserving condition's corners
  bool cornersTried = false;  // corners was computed (from the segmentation: a split can change it)
  size_t next = 0;           // the boundary conditions tried: order[0, next)
  bool flattened = false;    // by order[next - 1]
  bool splitAsked = false;   // its first condition failed and the patch is big enough to split
  std::vector<uint32_t> splitSeeds;  // input faces a split keeps apart: the first condition's worst crossing
  bool scaleSplit = false;   // flattened, with scale factors spreading more than maxScaleRatio
  double scaleRatio = 1;     // flattened: the spread of its scale factors (max / min)
  std::string lastError;
};

// The input vertex of patch mesh pm where the scale u (per vertex of pm) is smallest (kNone for
// no u); cutThroughSink refuses one on a curve (the conditions other than the free one move the
// border's scale).
uint32_t scaleSink(const F::PatchMesh& pm, const std::vector<double>& u) {
  if (u.size() != pm.vertexInput.size() || u.empty()) return kNone;
  return pm.vertexInput[size_t(std::min_element(u.begin(), u.end()) - u.begin())];
}

// The other sinks of a flattened patch a sink cut may pass through (input vertices): the local
// minima of u inside it (no vertex of its border) whose scale is below the patch's largest by
// more than `ratio`.
std::vector<uint32_t> otherSinks(const PatchWork& w, double ratio) {
  const auto& u = w.flat.u;
  const size_t nv = w.pm.vertexInput.size();
  if (u.size() != nv || w.scaleSub.size() != nv) return {};
  std::vector<uint8_t> candidate(nv, 1);
  for (const auto& loop : w.pm.boundaryLoops)
    for (const auto& h : loop) candidate[w.pm.mesh.triangles[3 * h.face + h.corner]] = 0;
  const auto& t = w.pm.mesh.triangles;
  for (size_t k = 0; k < t.size(); ++k) {  // a vertex with a lower neighbour (ties: the lower index) is none
    const uint32_t a = t[k], b = t[k - k % 3 + (k + 1) % 3];
    if (u[b] < u[a] || (u[b] == u[a] && b < a)) candidate[a] = 0;
    if (u[a] < u[b] || (u[a] == u[b] && a < b)) candidate[b] = 0;
  }
  const double top = *std::max_element(w.scaleSub.begin(), w.scaleSub.end());
  std::vector<uint32_t> sinks;
  for (size_t v = 0; v < nv; ++v)
    if (candidate[v] && top > ratio * w.scaleSub[v]) sinks.push_back(w.pm.vertexInput[v]);
  return sinks;
}

// The spread of a flattened patch's scale (max / min over its vertices: Flattening::scaleRatio).
double spreadOf(const PatchWork& w) {
  const auto [lo, hi] = std::minmax_element(w.scaleSub.begin(), w.scaleSub.end());
  return w.scaleSub.empty() ? 1.0 : *hi / *lo;
}

// Vertex v (input) is on an inner curve (features/segmentation.h).
bool onInnerCurve(const F::EdgeGraph& g, const F::Segmentation& seg, uint32_t v) {
  if (v == kNone) return false;
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
    if (seg.isInnerEdge(g.vertexEdgeIds[k])) return true;
  return false;
}

// The vertices of patch mesh pm too far from flat for its layout (input vertices, kNone for none):
// the border vertex whose 3D wedge is widest above 2π − kConeGap, and the interior vertex whose
// angle sum is smallest below it.
struct FarFromFlat {
  uint32_t widestCorner = kNone;
  uint32_t sharpestCone = kNone;
  double coneAngle = 2 * kPi;  // sharpestCone's angle sum
};

FarFromFlat farFromFlat(const F::PatchMesh& pm) {
  const std::vector<double> angle = cornerWedgeAngles(pm);
  std::vector<uint8_t> border(angle.size(), 0);
  for (const auto& loop : pm.boundaryLoops)
    for (const auto& h : loop) border[pm.mesh.triangles[3 * h.face + h.corner]] = 1;
  FarFromFlat far;
  double widest = 2 * kPi - kConeGap, sharpest = 2 * kPi - kConeGap;
  for (const auto& loop : pm.boundaryLoops)
    for (const auto& h : loop) {
      const uint32_t v = pm.mesh.triangles[3 * h.face + h.corner];
      if (angle[v] > widest) widest = angle[v], far.widestCorner = pm.vertexInput[v];
    }
  for (uint32_t v = 0; v < angle.size(); ++v)
    if (!border[v] && angle[v] < sharpest) sharpest = far.coneAngle = angle[v], far.sharpestCone = pm.vertexInput[v];
  return far;
}

// Whether more than half of `faces` are marked.
bool mostlyMarked(const std::vector<uint32_t>& faces, const std::vector<uint8_t>& mark) {
  size_t n = 0;
  for (const uint32_t f : faces) n += mark[f];
  return 2 * n > faces.size();
}

// A hash of which input edges are curves of which kind (FNV-1a).
uint64_t curveStateHash(const F::Segmentation& seg) {
  uint64_t h = 1469598103934665603ull;
  for (F::EdgeKind k : seg.edgeKind) h = (h ^ uint64_t(k)) * 1099511628211ull;
  return h;
}

// splitPatch, but a split that leaves no more patches than before (its repairs gave a part to a
// neighbour) and brings back a segmentation seen after such a split before is undone: the
// patch's next split would trade the same faces back and forth without end. `lateral` keeps
// the states those splits made.
bool splitOnce(Surface& surf, uint32_t p, std::set<uint64_t>& lateral, const std::vector<uint32_t>& seeds) {
  const size_t before = surf.seg.patches.size();
  const std::vector<F::EdgeKind> kinds = surf.seg.edgeKind;
  const uint32_t cuts = surf.seg.cutEdgeCount;
  if (!F::splitPatch(surf.g, surf.seg, p, 2, seeds)) return false;
  if (surf.seg.patches.size() > before || lateral.insert(curveStateHash(surf.seg)).second) return true;
  surf.seg.edgeKind = kinds;
  surf.seg.cutEdgeCount = cuts;
  F::rebuildCurves(surf.g, surf.seg);
  return false;
}

// The input faces beside the two boundary edges of the crossing of a failed layout that lie
// farthest apart along the border (most often two sides of a cut, or two cuts, that the flat map
// brings together): splitPatch parts them when the farthest points do not. A split that leaves
// them in one part keeps the overlap there: man's largest failing patch was split seven times
// over around the same crossing. Empty without a crossing.
std::vector<uint32_t> crossingSeeds(const F::PatchMesh& pm, const FlattenReport& r) {
  const auto& T = pm.mesh.triangles;
  // border position (loop, index) and face of the border edge a-b
  const auto find = [&](uint32_t a, uint32_t b, size_t& loop, size_t& at) {
    for (loop = 0; loop < pm.boundaryLoops.size(); ++loop)
      for (at = 0; at < pm.boundaryLoops[loop].size(); ++at) {
        const auto& h = pm.boundaryLoops[loop][at];
        const uint32_t x = T[3 * h.face + h.corner], y = T[3 * h.face + (h.corner + 1) % 3];
        if ((x == a && y == b) || (x == b && y == a)) return h.face;
      }
    return kNone;
  };
  std::vector<uint32_t> seeds;
  size_t widest = 0;
  for (const auto& c : r.boundaryCrossingEdges) {
    size_t la, ia, lb, ib;
    const uint32_t fa = find(c[0], c[1], la, ia), fb = find(c[2], c[3], lb, ib);
    if (fa == kNone || fb == kNone || fa == fb) continue;
    const size_t n = pm.boundaryLoops[la].size();
    const size_t gap = la != lb ? n : std::min(ia > ib ? ia - ib : ib - ia, n - (ia > ib ? ia - ib : ib - ia));
    if (gap > widest) widest = gap, seeds = {pm.faceInput[fa], pm.faceInput[fb]};
  }
  return seeds;
}

// Try the boundary conditions order[f.next...] on f.w->pm until one works; stop after a failure of
// order.front() when the patch may be split then (f.splitAsked). Errors of the flattening are
// kept in f.lastError; a cancel is thrown.
void tryConditions(const F::Segmentation& seg, const std::vector<BoundaryCondition>& order, size_t faces, Flattening& f) {
  while (f.next < order.size() && !f.flattened) {
    const BoundaryCondition bc = order[f.next++];
    FlattenOptions fo;
    fo.boundary = bc;
    fo.deferPullback = true;  // built once the patch is kept (flattenPatches' end)
    // an inner curve's edges stay edges of the layout: each is then a straight segment in the
    // plane, on which the pull-back is the projective map of that one edge (curve_samples.cpp).
    // Flipped away, an edge is a bent path in the plane: the chord between two of its samples
    // strays from it, and the pull-back of a point beside the chord lands across the crease
    // (elk at --feature-angle 20 --edge-length-rel 0.02: triangles below the bound beside inner
    // curves that each certificate round made smaller and more numerous, 39 s).
    for (const InnerCurve& ic : f.w->inner)
      for (size_t i = 0; i + 1 < ic.sub.size(); ++i) fo.keepEdges.push_back({ic.sub[i], ic.sub[i + 1]});
    if (bc == BoundaryCondition::Corners) {
      f.corners = boundaryCorners(seg, f.w->pm);
      f.cornersTried = true;
      if (f.corners.empty()) continue;
      fo.corners = f.corners;
    }
    try {
      fo.requireValidLayout = bc != order.front();  // the first condition's crossings seed a split
      f.w->flat = flatten(f.w->pm.mesh, fo);
      if (!f.w->flat.report.invalidLayout.empty()) fail(Code::NumericalFailure, Stage::Flatten, f.w->flat.report.invalidLayout);
      f.flattened = true;
    } catch (const Error& e) {
      if (e.code() == Code::Cancelled) throw;
      f.lastError = e.what();
      // the free boundary failed (its layout overlaps itself): smaller parts are closer to
      // developable and keep the least distorting map; split while the patch is big enough
      if (bc == order.front() && faces >= kMinSplitFaces) {
        f.splitAsked = true;
        f.splitSeeds = crossingSeeds(f.w->pm, f.w->flat.report);
        return;
      }
    }
  }
}

// Planar/3D scale and 3D target size per sub vertex of a flattened patch, the scale from the
// areas of the input faces around the vertex. Returns the spread of the scale (max / min).
double scaleAndSize(const Surface& surf, PatchWork& w) {
  const size_t nv = w.pm.vertexInput.size();
  std::vector<double> a2(nv, 0.0), a3(nv, 0.0);
  const auto& uv = w.flat.uv;
  for (size_t f = 0; f < w.pm.faceInput.size(); ++f) {
    const uint32_t* t = &w.pm.mesh.triangles[3 * f];
    double ax = uv[2 * t[1]] - uv[2 * t[0]], ay = uv[2 * t[1] + 1] - uv[2 * t[0] + 1];
    double bx = uv[2 * t[2]] - uv[2 * t[0]], by = uv[2 * t[2] + 1] - uv[2 * t[0] + 1];
    double area2 = std::abs(ax * by - ay * bx) * 0.5, area3 = surf.g.faceArea(w.pm.faceInput[f]);
    for (int c = 0; c < 3; ++c) a2[t[c]] += area2, a3[t[c]] += area3;
  }
  w.scaleSub.resize(nv);
  w.hSub.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    w.scaleSub[v] = a3[v] > 0 ? std::sqrt(a2[v] / a3[v]) : 1.0;
    w.hSub[v] = surf.sizing.h[w.pm.vertexInput[v]];
  }
  return spreadOf(w);
}

// Flattening f's scale spread measured, and whether it asks for a split.
void measureScale(const Surface& surf, const RemeshOptions& opt, Flattening& f) {
  f.scaleRatio = scaleAndSize(surf, *f.w);
  f.scaleSplit = f.scaleRatio > opt.maxScaleRatio;
}

// The patch of input faces `faces` extracted (cut open along `mask`) and flattened up to where a
// split may be made (Flattening).
Flattening flattenOne(const Surface& surf, const RemeshOptions& opt, const std::vector<uint8_t>& mask,
                      const std::vector<uint32_t>& faces) {
  Flattening f;
  try {
    f.w = std::make_unique<PatchWork>();
    f.w->pm = F::extractPatch(surf.g, mask, faces);
    if (!f.w->pm.isDisk()) fail(Code::InternalError, Stage::Flatten, "a patch is not a disk after cutting");
    f.w->inner = innerCurves(surf, f.w->pm);
    tryConditions(surf.seg, conditionOrder(opt.boundary), faces.size(), f);
    if (f.flattened) measureScale(surf, opt, f);
  } catch (...) {
    f.error = std::current_exception();
  }
  return f;
}

bool samePatchMesh(const F::PatchMesh& a, const F::PatchMesh& b) {
  if (a.boundaryLoops.size() != b.boundaryLoops.size()) return false;
  for (size_t l = 0; l < a.boundaryLoops.size(); ++l) {
    const auto &x = a.boundaryLoops[l], &y = b.boundaryLoops[l];
    if (x.size() != y.size()) return false;
    for (size_t k = 0; k < x.size(); ++k)
      if (x[k].face != y[k].face || x[k].corner != y[k].corner) return false;
  }
  return a.mesh.positions == b.mesh.positions && a.mesh.triangles == b.mesh.triangles && a.faceInput == b.faceInput &&
         a.vertexInput == b.vertexInput && a.eulerCharacteristic == b.eulerCharacteristic && a.pinched == b.pinched;
}

// A flattening made before a split elsewhere is the one the patch gets now when its extraction is
// the same and so are the corners its corner-preserving condition used (a split can add corners).
bool stillValid(const Surface& surf, const std::vector<uint8_t>& mask, const std::vector<uint32_t>& faces, const Flattening& f) {
  if (f.error || !f.w) return false;
  const F::PatchMesh pm = F::extractPatch(surf.g, mask, faces);
  if (!samePatchMesh(pm, f.w->pm)) return false;
  return !f.cornersTried || boundaryCorners(surf.seg, pm) == f.corners;
}

}  // namespace

Patches flattenPatches(Surface& surf, const RemeshOptions& opt, const Progress& progress, RemeshReport& rep) {
  // flattened patches by their exact face set: splitting a patch can reroute the cuts of its
  // neighbours (improveCutJunctions), which changes their faces and so their flattening
  std::map<std::vector<uint32_t>, std::unique_ptr<PatchWork>> cache;
  // flattenings made after the first split of a round, checked before use in the next (stillValid)
  std::map<std::vector<uint32_t>, Flattening> spare;
  // each patch's sorted faces, by its smallest face (the first listed): a patch the splits left
  // alone keeps its key from round to round instead of being sorted again
  std::map<uint32_t, std::pair<std::vector<uint32_t>, std::vector<uint32_t>>> keys;
  auto keyOf = [&keys](const std::vector<uint32_t>& faces) -> const std::vector<uint32_t>& {
    auto& [listed, sorted] = keys[faces[0]];
    if (listed != faces) {
      listed = faces;
      sorted = faces;
      std::sort(sorted.begin(), sorted.end());
    }
    return sorted;
  };
  const std::vector<BoundaryCondition> order = conditionOrder(opt.boundary);
  // Patches are flattened a window ahead of the patch order. A split ends the round; the
  // flattenings after it serve the next round only where the split's repairs left the patch as it
  // was (stillValid): the window bounds that loss, one thread none, while 4 patches per thread
  // are enough to balance them, unless one is as large as the others together (fandisk's largest
  // is about half of its flattening): the window then grows until its faces are `threads` times
  // its largest patch's.
  const unsigned threads = resolveThreads(unsigned(opt.threads));
  const size_t window = threads <= 1 ? 1 : 4 * size_t(threads);
  const auto windowEnd = [&](const std::vector<uint32_t>& todo, size_t from) {
    size_t to = std::min(todo.size(), from + window);
    if (threads <= 1) return to;
    size_t faces = 0, largest = 0;
    for (size_t i = from; i < to; ++i) {
      faces += surf.seg.patches[todo[i]].size();
      largest = std::max(largest, surf.seg.patches[todo[i]].size());
    }
    for (; to < todo.size() && faces < threads * largest; ++to) {
      faces += surf.seg.patches[todo[to]].size();
      largest = std::max(largest, surf.seg.patches[todo[to]].size());
    }
    return to;
  };
  double reported = 0;  // progress stays monotone across the parallel and the ordered part
  const auto advance = [&](double f) {
    reported = std::max(reported, f);
    progress.check(Stage::Flatten, reported);
  };
  // each round flattens what is new and splits at most one patch: the rounds are capped by the
  // patches the segmentation may make (a split that undoes another would otherwise cycle)
  const uint32_t maxPatches = F::FeatureOptions{}.maxPatches;
  const double minWedge = 2 * opt.minAngle * kPi / 180;  // each side of a cut through a vertex
  // an interior vertex whose angle sum is below this is a spike tip (kSpikeTipFan)
  const double spikeAngle = kSpikeTipFan * opt.minAngle * kPi / 180;
  std::set<uint64_t> lateral;  // segmentations left by splits that made no more patches
  // per input face: in a patch cut through a vertex far from flat because its layout overlapped
  std::vector<uint8_t> overlapCut(surf.g.faceCount, 0);
  int joinRounds = 0;  // of joining narrow patches (kJoinWidth)
  // the faces the joined patches may still hold: each is flattened again, and together they cost
  // at most one more flattening of the whole input
  size_t joinFaces = surf.g.faceCount;
  std::vector<uint8_t> kept;  // per edge: a cut a join made plain that was restored
  // each joined patch by its key: the cut edges the join made plain (restored when its flattening
  // is worse than its parts'), its parts' largest scale spread and smallest interior angle sum
  struct Join {
    std::vector<uint32_t> plain;
    double spread = 1, cone = 2 * kPi;
  };
  std::map<std::vector<uint32_t>, Join> joins;
  for (int round = 0;; ++round) {
    if (round > 64 + 2 * int(maxPatches) || surf.seg.patches.size() > maxPatches)
      fail(Code::IterationLimit, Stage::Flatten,
           "splitting patches for their scale factor did not settle (" + std::to_string(surf.seg.patches.size()) + " patches after " +
               std::to_string(round) + " rounds)");
    const auto mask = surf.seg.curveMask();
    // the patches not flattened yet, in patch order
    std::vector<uint32_t> todo;
    std::vector<std::vector<uint32_t>> todoFaces;  // their faces, sorted (the key of cache and spare)
    std::vector<Flattening> made;
    for (uint32_t p = 0; p < surf.seg.patches.size(); ++p) {
      const auto& key = keyOf(surf.seg.patches[p]);
      if (cache.count(key)) continue;
      todo.push_back(p);
      todoFaces.push_back(key);
      auto it = spare.find(key);
      made.emplace_back();
      if (it != spare.end() && stillValid(surf, mask, surf.seg.patches[p], it->second)) made.back() = std::move(it->second);
    }
    spare.clear();
    const double total = double(surf.seg.patches.size() + 1);
    bool split = false;
    std::vector<std::vector<uint32_t>> undo;  // the keys of the joined patches to take apart
    for (size_t from = 0, to = 0; from < todo.size() && !split; from = to) {
      // the next window of them flattened apart, on the threads (largest first) ...
      to = windowEnd(todo, from);
      std::vector<double> cost(to - from);
      for (size_t i = from; i < to; ++i) cost[i - from] = made[i].w ? 0.0 : double(surf.seg.patches[todo[i]].size());
      const std::vector<size_t> byCost = largestFirst(cost);
      const size_t before = cache.size();
      parallelFor(
          to - from, unsigned(opt.threads),
          [&](size_t k) {
            const size_t i = from + byCost[k];
            if (!made[i].w) made[i] = flattenOne(surf, opt, mask, surf.seg.patches[todo[i]]);
          },
          [&](size_t done) { advance(double(before + done) / total); });
      // ... then taken in patch order, as a serial loop would: the first patch that is split ends
      // the round (the segmentation changes), and the flattenings after it are kept for the next
      for (size_t i = from; i < to && !split; ++i) {
        const uint32_t p = todo[i];
        // a copy: a split that is undone rebuilds seg.patches, which may have grown meanwhile
        const std::vector<uint32_t> faces = surf.seg.patches[p];
        Flattening& f = made[i];
        if (f.error) std::rethrow_exception(f.error);
        // a joined patch flattened worse than its parts: the join undone at the end of the round
        // (kJoinWidth), its parts' flattenings kept
        if (const auto join = joins.find(keyOf(faces)); join != joins.end()) {
          const Join& j = join->second;
          if (!f.flattened || f.splitAsked || f.scaleSplit || f.scaleRatio > std::max(kSinkScaleRatio, j.spread) ||
              farFromFlat(f.w->pm).coneAngle < std::min(spikeAngle, j.cone)) {
            undo.push_back(join->first);
            continue;
          }
        }
        // a flattening that fails or spreads its scale too far with creases inside: those creases
        // continued until they close their parts off first, as the segmentation does without
        // inner creases (features/segmentation.h)
        if ((f.splitAsked || !f.flattened || f.scaleSplit) && F::closeInnerCreases(surf.g, surf.seg, p)) {
          ++rep.patchSplitsForScale;
          split = true;
          continue;
        }
        // a failed flattening: cut through a vertex too far from flat (kConeGap) before splitting
        // around it; but a layout that still overlaps itself after such a cut in the patch it came
        // from is split at its crossing: the cut did not remove the overlap, and the next vertex
        // far from flat would not either (armadillo: five such cuts in turn, each shaving 20–240
        // faces off a patch of 10,318 that overlapped itself after each)
        const bool overlaps = !f.splitSeeds.empty();
        const FarFromFlat far = f.splitAsked || !f.flattened ? farFromFlat(f.w->pm) : FarFromFlat{};
        if ((f.splitAsked || !f.flattened) && !(overlaps && mostlyMarked(faces, overlapCut)) &&
            (F::cutThroughWideCorner(surf.g, surf.seg, p, far.widestCorner, minWedge) ||
             F::cutThroughSink(surf.g, surf.seg, p, far.sharpestCone, minWedge))) {
          if (overlaps)
            for (const uint32_t t : faces) overlapCut[t] = 1;
          ++rep.patchSplitsForScale;
          rep.warnings.push_back("patch cut through a vertex far from flat after: " + f.lastError);
          split = true;
          continue;
        }
        for (const uint32_t t : faces) overlapCut[t] = 0;  // its parts may try a cut again
        if (f.splitAsked) {
          if (splitOnce(surf, p, lateral, f.splitSeeds)) {
            ++rep.patchSplitsForScale;
            rep.warnings.push_back("patch split after its first boundary condition failed: " + f.lastError);
            split = true;
            continue;
          }
          // no split to be had: the other conditions
          f.splitAsked = false;
          tryConditions(surf.seg, order, 0, f);
          if (f.flattened) measureScale(surf, opt, f);
        }
        if (!f.flattened) {
          // every boundary condition failed (a layout that overlaps itself or a flow that stalls):
          // split the patch and retry
          if (faces.size() < kMinSplitFaces || !splitOnce(surf, p, lateral, f.splitSeeds))
            fail(Code::NumericalFailure, Stage::Flatten, "patch " + std::to_string(p) + " could not be flattened: " + f.lastError);
          ++rep.patchSplitsForScale;
          rep.warnings.push_back("patch split after a flattening failure: " + f.lastError);
          split = true;
          continue;
        }
        if (f.next > 1)
          rep.warnings.push_back(std::string("patch flattened with the ") + conditionName(order[f.next - 1]) +
                                 " boundary condition after: " + f.lastError + " [patch of " + std::to_string(faces.size()) + " faces]");
        // a spike tip inside the patch: the flat map opens its angle sum Θ to 2π, so the angles
        // of the triangles around it shrink by Θ/2π when lifted, and the output need not have a
        // vertex at the tip; cut through it, and each half lays out its side of the tip as it is
        // (each side keeps the bound: a wedge below twice the bound takes one triangle); a tip on
        // an inner curve is no vertex a cut may pass: the inner curves are closed instead
        if (const FarFromFlat far = farFromFlat(f.w->pm);
            far.coneAngle < spikeAngle && (F::cutThroughSpike(surf.g, surf.seg, p, far.sharpestCone, 0.5 * minWedge) ||
                                           (onInnerCurve(surf.g, surf.seg, far.sharpestCone) && F::closeInnerCreases(surf.g, surf.seg, p)))) {
          ++rep.sinkCuts;
          split = true;
          continue;
        }
        if (const uint32_t sink = scaleSink(f.w->pm, f.w->flat.u);
            f.scaleRatio > kSinkScaleRatio && sink != kNone &&
            F::cutThroughSink(surf.g, surf.seg, p, sink, minWedge, kSinkDepth * surf.sizing.h[sink],
                              otherSinks(*f.w, kSinkScaleRatio))) {
          ++rep.sinkCuts;
          split = true;
          continue;
        }
        if (f.scaleSplit && faces.size() >= kMinSplitFaces && splitOnce(surf, p, lateral, {})) {
          ++rep.patchSplitsForScale;
          split = true;
          continue;
        }
        cache.emplace(keyOf(faces), std::move(f.w));
        advance(double(cache.size()) / total);
      }
    }
    // the flattenings a split left unused (this window's and those a spare gave later windows),
    // by the faces they were made of: the patch numbers changed with the split
    for (size_t i = 0; split && i < todo.size(); ++i)
      if (made[i].w && !made[i].error) spare.emplace(todoFaces[i], std::move(made[i]));
    // a join is undone only where the round left its patch as it was (a split's repairs may
    // have rerouted a cut through it; the patch is then flattened again as it is)
    for (const auto& key : undo) {
      const auto join = joins.find(key);
      const std::vector<uint32_t>& plain = join->second.plain;
      if (keyOf(surf.seg.patches[surf.seg.facePatch[surf.g.edgeFaces[plain[0]][0]]]) != key) continue;
      for (const uint32_t e : plain) surf.seg.edgeKind[e] = F::EdgeKind::Cut, kept[e] = 1;
      surf.seg.cutEdgeCount += uint32_t(plain.size());
      joins.erase(join);
      --rep.patchJoins;
    }
    if (!undo.empty()) F::rebuildCurves(surf.g, surf.seg);
    if (split || !undo.empty()) continue;
    if (joinRounds < kJoinRounds) {
      ++joinRounds;
      kept.resize(surf.g.edgeCount(), 0);
      joins.clear();
      const std::vector<F::EdgeKind> before = surf.seg.edgeKind;
      const std::vector<uint32_t> partOf = surf.seg.facePatch;
      const std::vector<std::vector<uint32_t>> parts = surf.seg.patches;
      if (F::mergeCutPatches(surf.g, surf.seg, kJoinWidth * surf.seg.junctionScale, {}, kept, true, joinFaces) > 0) {
        F::rebuildCurves(surf.g, surf.seg);
        std::map<uint32_t, Join> made;  // by the joined patch
        for (uint32_t e = 0; e < before.size(); ++e)
          if (before[e] != surf.seg.edgeKind[e]) made[surf.seg.facePatch[surf.g.edgeFaces[e][0]]].plain.push_back(e);
        std::vector<uint8_t> seen(parts.size(), 0);
        for (auto& [q, j] : made)
          for (const uint32_t f : surf.seg.patches[q])
            if (!seen[partOf[f]]) {
              seen[partOf[f]] = 1;
              const PatchWork& w = *cache.at(keyOf(parts[partOf[f]]));
              j.spread = std::max(j.spread, spreadOf(w));
              j.cone = std::min(j.cone, farFromFlat(w.pm).coneAngle);
            }
        for (auto& [q, j] : made) {
          joinFaces -= surf.seg.patches[q].size();
          joins.emplace(keyOf(surf.seg.patches[q]), std::move(j));
        }
        rep.patchJoins += made.size();
        continue;
      }
    }
    Patches work;
    for (const auto& faces : surf.seg.patches) work.push_back(std::move(cache.at(keyOf(faces))));
    // the same edges as at its flattening (the patch and its cuts are the same), under the curve
    // ids of the final segmentation
    for (auto& w : work) w->inner = innerCurves(surf, w->pm);
    // the pull-backs of the flattenings kept (most of those made were dropped for a cut)
    parallelFor(work.size(), unsigned(opt.threads), [&](size_t i) { finishPullback(work[i]->flat); });
    return work;
  }
}

}  // namespace conformesh::pipeline
