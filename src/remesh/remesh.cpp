#include "remesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "conformal/flatten.h"
#include "features/curve_mesh.h"
#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "mesh/validate.h"
#include "planar/refine.h"
#include "quality/metrics.h"
#include "remesh/limits.h"

namespace conformesh {
namespace {

namespace F = features;
using F::kNone;
constexpr double kPi = 3.14159265358979323846;

double elapsed(std::chrono::steady_clock::time_point& t) {
  auto now = std::chrono::steady_clock::now();
  double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

// A spot where the 3D angle certificate asks for smaller planar triangles: h <= h0 + |x − c|/2.
struct Spot {
  double x, y, h;
};

// One patch: its sub-mesh, flattening, boundary condition, sizing, and its latest meshing.
struct PatchWork {
  F::PatchMesh pm;
  FlatPatch flat;
  std::vector<double> hSub;      // 3D target length per sub vertex
  std::vector<double> scaleSub;  // planar length per 3D length, per sub vertex
  std::vector<Spot> spots;
  std::vector<std::pair<uint32_t, double>> bcCorners;  // sub vertex, planar target angle
  std::vector<double> wedgeAngle;                      // 3D angle sum per sub vertex
  // latest meshing
  std::vector<uint32_t> localToGlobal;  // planar vertex -> output vertex (samples first)
  std::vector<F::Vec3> interiorPositions;  // positions of planar vertices that are interior
  std::vector<uint32_t> triangles;         // planar triangles (local indices)
  std::vector<double> planarPoints;        // planar positions of the latest meshing
  uint64_t builtAt = 0;
  bool needsMesh = true;  // full refinement (first time, or the certificate asked for spots)
  bool dirty = false;     // a neighbour added curve samples on this patch's boundary

};

struct BoundaryPoint {
  uint32_t sample;
  uint32_t loopPos;  // boundary halfedge index in the loop
  double param;      // along that halfedge from its tail
  double x, y;
};

class Pipeline {
 public:
  Pipeline(const RemeshOptions& o, const ProgressFn& p) : opt_(o), progress_(p) {}
  RemeshResult run(const MeshBuffers& input);

 private:
  void checkCancel(Stage s, double f) {
    if (progress_ && !progress_(s, std::clamp(f, 0.0, 1.0))) fail(Code::Cancelled, s, "cancelled by the progress callback");
  }
  void ensurePatchCorners();
  void flattenPatches();
  std::vector<std::pair<uint32_t, double>> boundaryCorners(const F::PatchMesh& pm) const;
  void indexSamples();
  std::vector<BoundaryPoint> boundaryPoints(const PatchWork& w) const;
  void meshPatch(uint32_t p);
  void patchUp(uint32_t p);
  uint32_t addSplitSample(const PatchWork& w, const std::vector<BoundaryPoint>& bp, uint32_t s, double t);
  double curveKey(uint32_t c, uint32_t sample) const;
  MeshBuffers stitch(std::vector<uint32_t>& trianglePatch) const;
  std::vector<double> cornerWedgeAngles(const F::PatchMesh& pm) const;

  const RemeshOptions& opt_;
  const ProgressFn& progress_;
  F::EdgeGraph g_;
  F::Segmentation seg_;
  F::SizingField sizing_;
  F::CurveMesh cm_;
  std::vector<std::unique_ptr<PatchWork>> work_;
  std::vector<std::vector<uint32_t>> edgeSamples_;  // interior samples per input edge
  std::vector<uint32_t> vertexSample_;              // sample at an input vertex
  std::vector<uint32_t> edgeIndexInCurve_;
  uint64_t stamp_ = 0;
  size_t scaleSplits_ = 0;
  double liftSeconds_ = 0;
  RemeshReport rep_;
};

std::vector<double> Pipeline::cornerWedgeAngles(const F::PatchMesh& pm) const {
  std::vector<double> a(pm.vertexInput.size(), 0.0);
  const auto& P = pm.mesh.positions;
  for (size_t f = 0; f < pm.faceInput.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      uint32_t v[3] = {pm.mesh.triangles[3 * f + c], pm.mesh.triangles[3 * f + (c + 1) % 3],
                       pm.mesh.triangles[3 * f + (c + 2) % 3]};
      F::Vec3 p0{P[3 * v[0]], P[3 * v[0] + 1], P[3 * v[0] + 2]};
      F::Vec3 p1{P[3 * v[1]], P[3 * v[1] + 1], P[3 * v[1] + 2]};
      F::Vec3 p2{P[3 * v[2]], P[3 * v[2] + 1], P[3 * v[2] + 2]};
      a[v[0]] += F::angleBetween(p1 - p0, p2 - p0);
    }
  return a;
}

// Corners of the corner-preserving boundary condition: boundary wedges at curve corners whose 3D
// angle differs from π by more than 10° (or artificial corners), with target angles adjusted so
// that Σ (π − α) = 2π (Gauss–Bonnet for a flat disk with straight sides). Artificial and cut
// corners absorb most of the adjustment, feature corners little.
std::vector<std::pair<uint32_t, double>> Pipeline::boundaryCorners(const F::PatchMesh& pm) const {
  std::vector<double> angle = cornerWedgeAngles(pm);
  std::vector<uint32_t> ids;
  std::vector<double> alpha, weight;
  std::vector<uint8_t> onBoundary(pm.vertexInput.size(), 0);
  for (const auto& h : pm.boundaryLoops[0]) onBoundary[pm.mesh.triangles[3 * h.face + h.corner]] = 1;
  for (uint32_t v = 0; v < pm.vertexInput.size(); ++v) {
    if (!onBoundary[v]) continue;
    uint32_t iv = pm.vertexInput[v];
    uint8_t kind = seg_.vertexCorner[iv];
    if (kind == 0) continue;
    if (kind == 1 && std::abs(angle[v] - kPi) < 10.0 * kPi / 180.0) continue;
    bool cut = false;
    for (uint32_t k = g_.vertexEdgeStart[iv]; k < g_.vertexEdgeStart[iv + 1]; ++k)
      cut = cut || seg_.edgeKind[g_.vertexEdgeIds[k]] == F::EdgeKind::Cut;
    ids.push_back(v);
    alpha.push_back(angle[v]);
    weight.push_back(kind == 2 || cut ? 1.0 : 0.15);
  }
  if (ids.size() < 3) return {};
  // distribute the Gauss–Bonnet deficit, keeping every angle in [15°, 345°]
  const double lo = 15.0 * kPi / 180.0, hi = 2 * kPi - lo;
  std::vector<double> a = alpha;
  std::vector<uint8_t> frozen(a.size(), 0);
  for (int it = 0; it < 20; ++it) {
    double sum = 0, wsum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      sum += kPi - a[i];
      if (!frozen[i]) wsum += weight[i];
    }
    double d = 2 * kPi - sum;  // increase Σ(π − α) by d: decrease α
    if (std::abs(d) < 1e-13) break;
    if (wsum == 0) return {};
    bool clamped = false;
    for (size_t i = 0; i < a.size(); ++i) {
      if (frozen[i]) continue;
      double na = a[i] - d * weight[i] / wsum;
      if (na < lo || na > hi) {
        na = std::clamp(na, lo, hi);
        frozen[i] = 1;
        clamped = true;
      }
      a[i] = na;
    }
    if (!clamped) break;
  }
  double sum = 0;
  for (double x : a) sum += kPi - x;
  if (std::abs(sum - 2 * kPi) > 1e-9) return {};
  std::vector<std::pair<uint32_t, double>> out;
  for (size_t i = 0; i < ids.size(); ++i) out.push_back({ids[i], a[i]});
  return out;
}

// Give every patch with fewer than 3 usable boundary-condition corners artificial corners
// (midpoints of the largest gaps by arc length) until it has 4.
void Pipeline::ensurePatchCorners() {
  auto mask = seg_.curveMask();
  bool changed = false;
  for (const auto& faces : seg_.patches) {
    F::PatchMesh pm = F::extractPatch(g_, mask, faces);
    if (boundaryCorners(pm).size() >= 3) continue;
    std::vector<double> angle = cornerWedgeAngles(pm);
    const auto& loop = pm.boundaryLoops[0];
    std::vector<uint32_t> verts;
    std::vector<double> arc{0.0};
    for (const auto& h : loop) {
      uint32_t a = pm.mesh.triangles[3 * h.face + h.corner], b = pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
      verts.push_back(a);
      arc.push_back(arc.back() + g_.edgeLength(g_.findEdge(pm.vertexInput[a], pm.vertexInput[b])));
    }
    std::vector<size_t> cornerPos;
    for (size_t i = 0; i < verts.size(); ++i) {
      uint32_t iv = pm.vertexInput[verts[i]];
      if (seg_.vertexCorner[iv] == 2 ||
          (seg_.vertexCorner[iv] == 1 && std::abs(angle[verts[i]] - kPi) >= 10.0 * kPi / 180.0))
        cornerPos.push_back(i);
    }
    const double L = arc.back();
    while (cornerPos.size() < 4 && cornerPos.size() < verts.size()) {
      double target;
      if (cornerPos.empty()) target = 0;
      else {
        double bestGap = -1;
        target = 0;
        for (size_t k = 0; k < cornerPos.size(); ++k) {
          double s0 = arc[cornerPos[k]];
          double s1 = k + 1 < cornerPos.size() ? arc[cornerPos[k + 1]] : arc[cornerPos[0]] + L;
          if (s1 - s0 > bestGap) bestGap = s1 - s0, target = std::fmod(0.5 * (s0 + s1), L);
        }
      }
      size_t best = kNone;
      for (size_t i = 0; i < verts.size(); ++i) {
        if (std::find(cornerPos.begin(), cornerPos.end(), i) != cornerPos.end()) continue;
        double d = std::abs(arc[i] - target);
        d = std::min(d, L - d);
        if (best == kNone || d < std::min(std::abs(arc[best] - target), L - std::abs(arc[best] - target))) best = i;
      }
      if (best == kNone) break;
      cornerPos.push_back(best);
      std::sort(cornerPos.begin(), cornerPos.end());
      if (seg_.forcedCorner.empty()) seg_.forcedCorner.assign(g_.vertexCount, 0);
      seg_.forcedCorner[pm.vertexInput[verts[best]]] = 1;
      changed = true;
    }
  }
  if (changed) F::rebuildCurves(g_, seg_);
}

void Pipeline::flattenPatches() {
  std::map<std::pair<uint32_t, size_t>, std::unique_ptr<PatchWork>> cache;
  for (int round = 0;; ++round) {
    if (round > 64 + int(g_.faceCount))
      fail(Code::IterationLimit, Stage::Flatten, "splitting patches for their scale factor did not settle");
    ensurePatchCorners();
    auto mask = seg_.curveMask();
    bool split = false;
    for (uint32_t p = 0; p < seg_.patches.size() && !split; ++p) {
      const auto& faces = seg_.patches[p];
      auto key = std::make_pair(*std::min_element(faces.begin(), faces.end()), faces.size());
      if (cache.count(key)) continue;
      auto w = std::make_unique<PatchWork>();
      w->pm = F::extractPatch(g_, mask, faces);
      if (!w->pm.isDisk()) fail(Code::InternalError, Stage::Flatten, "a patch is not a disk after cutting");
      FlattenOptions fo;
      fo.corners = boundaryCorners(w->pm);
      w->bcCorners = fo.corners;
      w->wedgeAngle = cornerWedgeAngles(w->pm);
      fo.boundary = fo.corners.empty() ? BoundaryCondition::Circle : BoundaryCondition::Corners;
      if (fo.corners.empty()) rep_.warnings.push_back("patch with a round (circle) boundary condition: no usable corners");
      try {
        w->flat = flatten(w->pm.mesh, fo);
      } catch (const Error& e) {
        // a layout that overlaps itself (or a flow that stalls): split the patch and retry
        if (e.code() == Code::Cancelled || faces.size() < 16 || !F::splitPatch(g_, seg_, p)) throw;
        ++scaleSplits_;
        rep_.warnings.push_back(std::string("patch split after a flattening failure: ") + e.what());
        split = true;
        break;
      }
      if (std::getenv("CONFORMESH_DEBUG3")) {
        const auto& loop = w->pm.boundaryLoops[0];
        const auto& uv = w->flat.uv;
        double worst = 0;
        size_t n = loop.size();
        std::vector<uint8_t> isC(w->pm.vertexInput.size(), 0);
        for (auto& c : fo.corners) isC[c.first] = 1;
        for (size_t k = 0; k < n; ++k) {
          auto vh = [&](size_t kk) { const auto& h = loop[kk % n]; return w->pm.mesh.triangles[3 * h.face + h.corner]; };
          uint32_t a = vh(k + n - 1), b = vh(k), c = vh(k + 1);
          if (isC[b]) continue;
          double ax = uv[2 * b] - uv[2 * a], ay = uv[2 * b + 1] - uv[2 * a + 1], bx = uv[2 * c] - uv[2 * b], by = uv[2 * c + 1] - uv[2 * b + 1];
          worst = std::max(worst, std::abs(std::atan2(ax * by - ay * bx, ax * bx + ay * by)));
        }
        std::fprintf(stderr, "patch %u: %zu corners, max boundary turning at non-corners %.3g rad, iterations %d, err %.3g\n", p, fo.corners.size(), worst, w->flat.report.iterations, w->flat.report.maxCurvatureError);
      }
      // planar/3D scale per sub vertex from the areas of the input faces around it
      const size_t nv = w->pm.vertexInput.size();
      std::vector<double> a2(nv, 0.0), a3(nv, 0.0);
      const auto& uv = w->flat.uv;
      for (size_t f = 0; f < w->pm.faceInput.size(); ++f) {
        const uint32_t* t = &w->pm.mesh.triangles[3 * f];
        double ax = uv[2 * t[1]] - uv[2 * t[0]], ay = uv[2 * t[1] + 1] - uv[2 * t[0] + 1];
        double bx = uv[2 * t[2]] - uv[2 * t[0]], by = uv[2 * t[2] + 1] - uv[2 * t[0] + 1];
        double area2 = std::abs(ax * by - ay * bx) * 0.5, area3 = g_.faceArea(w->pm.faceInput[f]);
        for (int c = 0; c < 3; ++c) a2[t[c]] += area2, a3[t[c]] += area3;
      }
      w->scaleSub.resize(nv);
      w->hSub.resize(nv);
      double smin = INFINITY, smax = 0;
      for (size_t v = 0; v < nv; ++v) {
        w->scaleSub[v] = a3[v] > 0 ? std::sqrt(a2[v] / a3[v]) : 1.0;
        w->hSub[v] = sizing_.h[w->pm.vertexInput[v]];
        smin = std::min(smin, w->scaleSub[v]);
        smax = std::max(smax, w->scaleSub[v]);
      }
      if (smax > opt_.maxScaleRatio * smin && faces.size() >= 16) {
        if (F::splitPatch(g_, seg_, p)) {
          ++scaleSplits_;
          split = true;
          break;
        }
      }
      cache.emplace(key, std::move(w));
      checkCancel(Stage::Flatten, double(cache.size()) / double(seg_.patches.size() + 1));
    }
    if (split) continue;
    work_.clear();
    for (const auto& faces : seg_.patches) {
      auto key = std::make_pair(*std::min_element(faces.begin(), faces.end()), faces.size());
      work_.push_back(std::move(cache.at(key)));
    }
    return;
  }
}

void Pipeline::indexSamples() {
  edgeSamples_.assign(g_.edgeCount(), {});
  vertexSample_.assign(g_.vertexCount, kNone);
  for (uint32_t s = 0; s < cm_.samples.size(); ++s) {
    const auto& smp = cm_.samples[s];
    if (smp.vertex != kNone) vertexSample_[smp.vertex] = s;
    else edgeSamples_[smp.edge].push_back(s);
  }
  edgeIndexInCurve_.assign(g_.edgeCount(), kNone);
  for (const auto& c : seg_.curves)
    for (uint32_t i = 0; i < c.edges.size(); ++i) edgeIndexInCurve_[c.edges[i]] = i;
}

std::vector<BoundaryPoint> Pipeline::boundaryPoints(const PatchWork& w) const {
  std::vector<BoundaryPoint> out;
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  for (uint32_t k = 0; k < loop.size(); ++k) {
    const auto& h = loop[k];
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    uint32_t A = w.pm.vertexInput[a];
    uint32_t e = g_.faceEdges[w.pm.faceInput[h.face]][h.corner];
    if (vertexSample_[A] != kNone) out.push_back({vertexSample_[A], k, 0.0, uv[2 * a], uv[2 * a + 1]});
    std::vector<std::pair<double, uint32_t>> on;
    for (uint32_t s : edgeSamples_[e]) {
      double t = cm_.samples[s].t;
      on.push_back({g_.edgeVerts[e][0] == A ? t : 1.0 - t, s});
    }
    std::sort(on.begin(), on.end());
    for (auto [t, s] : on)
      out.push_back({s, k, t, uv[2 * a] + t * (uv[2 * b] - uv[2 * a]), uv[2 * a + 1] + t * (uv[2 * b + 1] - uv[2 * a + 1])});
  }
  return out;
}

double Pipeline::curveKey(uint32_t c, uint32_t s) const {
  const auto& cu = seg_.curves[c];
  const auto& ids = cm_.curveSamples[c];
  if (s == ids.front()) return 0.0;
  if (s == ids.back()) return double(cu.edges.size());
  const auto& smp = cm_.samples[s];
  uint32_t e = smp.edge;
  uint32_t i = edgeIndexInCurve_[e];
  double t = cu.vertices[i] == g_.edgeVerts[e][0] ? smp.t : 1.0 - smp.t;
  return double(i) + t;
}

// A refinement vertex inserted on boundary segment s (from boundary point s to s+1) at
// parameter t: find it on the patch boundary polyline in the plane, make it a curve sample on the
// input edge there, and ask the patches on the curve to include it.
uint32_t Pipeline::addSplitSample(const PatchWork& w, const std::vector<BoundaryPoint>& bp, uint32_t s, double t) {
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  const BoundaryPoint& p0 = bp[s];
  const BoundaryPoint& p1 = bp[(s + 1) % bp.size()];
  // pieces of the boundary polyline between p0 and p1: (halfedge, param from, param to)
  struct Piece {
    uint32_t k;
    double t0, t1;
  };
  std::vector<Piece> pieces;
  uint32_t k = p0.loopPos;
  double from = p0.param;
  for (size_t guard = 0; guard <= loop.size() + 1; ++guard) {
    if (k == p1.loopPos && (p1.param >= from || pieces.size() > 0 || bp.size() > 1)) {
      if (!(k == p0.loopPos && pieces.empty() && p1.param < from)) {
        pieces.push_back({k, from, p1.param});
        break;
      }
    }
    pieces.push_back({k, from, 1.0});
    k = (k + 1) % uint32_t(loop.size());
    from = 0.0;
  }
  auto halfedgeUv = [&](uint32_t kk, double tt, double& x, double& y) {
    const auto& h = loop[kk];
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    x = uv[2 * a] + tt * (uv[2 * b] - uv[2 * a]);
    y = uv[2 * a + 1] + tt * (uv[2 * b + 1] - uv[2 * a + 1]);
  };
  std::vector<double> len(pieces.size());
  double total = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    double x0, y0, x1, y1;
    halfedgeUv(pieces[i].k, pieces[i].t0, x0, y0);
    halfedgeUv(pieces[i].k, pieces[i].t1, x1, y1);
    len[i] = std::hypot(x1 - x0, y1 - y0);
    total += len[i];
  }
  double target = t * total, acc = 0;
  size_t i = 0;
  while (i + 1 < pieces.size() && acc + len[i] < target) acc += len[i++];
  double local = len[i] > 0 ? std::clamp((target - acc) / len[i], 0.0, 1.0) : 0.5;
  double th = pieces[i].t0 + local * (pieces[i].t1 - pieces[i].t0);
  const auto& h = loop[pieces[i].k];
  uint32_t A = w.pm.vertexInput[w.pm.mesh.triangles[3 * h.face + h.corner]];
  uint32_t e = g_.faceEdges[w.pm.faceInput[h.face]][h.corner];
  F::CurveSample smp;
  smp.edge = e;
  smp.t = g_.edgeVerts[e][0] == A ? th : 1.0 - th;
  if (smp.t <= 0.0 || smp.t >= 1.0) {
    uint32_t v = smp.t <= 0.0 ? g_.edgeVerts[e][0] : g_.edgeVerts[e][1];
    if (vertexSample_[v] != kNone) return vertexSample_[v];
    smp.t = smp.t <= 0.0 ? 0.0 : 1.0;
    smp.vertex = v;
  }
  smp.position = g_.positions[g_.edgeVerts[e][0]] * (1.0 - smp.t) + g_.positions[g_.edgeVerts[e][1]] * smp.t;
  uint32_t id = uint32_t(cm_.samples.size());
  cm_.samples.push_back(smp);
  if (smp.vertex != kNone) vertexSample_[smp.vertex] = id;
  else edgeSamples_[e].push_back(id);
  uint32_t c = seg_.edgeCurve[e];
  auto& ids = cm_.curveSamples[c];
  double key = curveKey(c, id);
  size_t pos = 1;
  while (pos + 1 < ids.size() && curveKey(c, ids[pos]) < key) ++pos;
  ids.insert(ids.begin() + long(pos), id);
  if (std::getenv("CONFORMESH_DEBUG4")) {
    uint32_t c0 = seg_.edgeCurve[cm_.samples[p0.sample].edge], c1 = seg_.edgeCurve[cm_.samples[p1.sample].edge];
    std::fprintf(stderr, "split seg %u (samples %u -> %u, curves %u %u) t=%.3f -> sample %u on curve %u key %.3f; keys ends %.3f %.3f; pieces %zu\n", s, p0.sample, p1.sample, c0, c1, t, id, c,
                 key, std::find(ids.begin(), ids.end(), p0.sample) != ids.end() ? curveKey(c, p0.sample) : -1.0,
                 std::find(ids.begin(), ids.end(), p1.sample) != ids.end() ? curveKey(c, p1.sample) : -1.0, pieces.size());
  }
  ++stamp_;
  for (uint32_t q : seg_.curves[c].patches)
    if (q != kNone && work_[q]->builtAt < stamp_) work_[q]->dirty = true;
  return id;
}

void Pipeline::meshPatch(uint32_t p) {
  PatchWork& w = *work_[p];
  w.builtAt = ++stamp_;
  w.dirty = false;
  w.needsMesh = false;
  std::vector<BoundaryPoint> bp = boundaryPoints(w);
  if (bp.size() < 3) fail(Code::InternalError, Stage::Refine, "a patch boundary has fewer than 3 samples");
  planar::Pslg pslg;
  for (const auto& b : bp) pslg.points.insert(pslg.points.end(), {b.x, b.y});
  for (uint32_t i = 0; i < bp.size(); ++i) pslg.segments.insert(pslg.segments.end(), {i, uint32_t((i + 1) % bp.size())});
  // At a boundary-condition corner whose planar angle differs much from its 3D angle, a single
  // planar triangle there would carry the whole distortion: put a point on the bisector so the
  // corner fan has at least two triangles.
  {
    std::map<uint32_t, double> target(w.bcCorners.begin(), w.bcCorners.end());
    const auto& loop = w.pm.boundaryLoops[0];
    const size_t n = bp.size();
    for (size_t i = 0; i < n; ++i) {
      if (bp[i].param != 0.0) continue;
      const auto& h = loop[bp[i].loopPos];
      uint32_t sv = w.pm.mesh.triangles[3 * h.face + h.corner];
      auto it = target.find(sv);
      if (it == target.end() || std::abs(it->second - w.wedgeAngle[sv]) < 15.0 * kPi / 180.0) continue;
      if (seg_.vertexCorner[w.pm.vertexInput[sv]] != 2 || it->second > w.wedgeAngle[sv]) continue;
      const BoundaryPoint& Q = bp[(i + n - 1) % n];
      const BoundaryPoint& R = bp[(i + 1) % n];
      double rx = R.x - bp[i].x, ry = R.y - bp[i].y, qx = Q.x - bp[i].x, qy = Q.y - bp[i].y;
      double lr = std::hypot(rx, ry), lq = std::hypot(qx, qy);
      if (lr == 0 || lq == 0) continue;
      double theta = std::atan2(rx * qy - ry * qx, rx * qx + ry * qy);
      if (theta <= 0) theta += 2 * kPi;
      double c = std::cos(0.5 * theta), sn = std::sin(0.5 * theta);
      double d = 0.5 * std::min(lr, lq);
      pslg.points.insert(pslg.points.end(), {bp[i].x + d * (c * rx - sn * ry) / lr, bp[i].y + d * (sn * rx + c * ry) / lr});
    }
  }
  planar::RefineOptions ro;
  ro.minAngleDeg = std::min(opt_.minAngleDeg, 34.0);
  // Longest-edge bound of the refinement vs the mean edge length it gives: calibrated so the
  // mean output edge length in flat regions is the target.
  const double kSizeFactor = 1.3;
  const Pullback& pb = w.flat.pullback;
  ro.sizing = [&](double x, double y) {
    PullbackPoint q;
    if (!pb.locate(x, y, q, 1e-6)) return double(INFINITY);
    double h = 0, s = 0;
    for (int c = 0; c < 3; ++c) {
      uint32_t v = w.pm.mesh.triangles[3 * q.face + c];
      h += q.bary[c] * w.hSub[v];
      s += q.bary[c] * w.scaleSub[v];
    }
    double hp = kSizeFactor * h * s;
    for (const Spot& sp : w.spots) hp = std::min(hp, sp.h + 0.5 * std::hypot(x - sp.x, y - sp.y));
    return hp;
  };
  double area3 = 0;
  for (uint32_t f : w.pm.faceInput) area3 += g_.faceArea(f);
  ro.maxInsertions = size_t(std::min(4e7, 50.0 * area3 / (sizing_.minLength * sizing_.minLength) + 1e5));
  planar::RefineResult rr = planar::refinePslg(pslg, ro);
  if (!rr.status.ok()) fail(rr.status.code, Stage::Refine, "patch " + std::to_string(p) + ": " + rr.status.message);
  const auto& pmsh = rr.mesh;
  auto tl = std::chrono::steady_clock::now();
  const size_t nv = pmsh.vertexCount();
  w.localToGlobal.assign(nv, kNone);
  w.interiorPositions.assign(nv, F::Vec3{});
  std::vector<uint8_t> onBoundary(nv, 0);
  {
    std::unordered_map<uint64_t, int> cnt;
    const auto& T = pmsh.triangles;
    for (size_t t = 0; t < T.size(); t += 3)
      for (int c = 0; c < 3; ++c) {
        uint64_t a = T[t + c], b = T[t + (c + 1) % 3];
        ++cnt[std::min(a, b) << 32 | std::max(a, b)];
      }
    for (const auto& [k, n] : cnt)
      if (n == 1) onBoundary[k >> 32] = onBoundary[k & 0xffffffffu] = 1;
  }
  for (size_t v = 0; v < nv; ++v) {
    if (v < bp.size()) {
      w.localToGlobal[v] = bp[v].sample;
      continue;
    }
    if (onBoundary[v]) {
      // a Steiner vertex on a boundary segment: its segment and parameter by projection (robust
      // whatever direction the refinement stores the segment in)
      double best = INFINITY, bt = 0;
      uint32_t bs = 0;
      for (uint32_t sgm = 0; sgm < bp.size(); ++sgm) {
        const auto& a = bp[sgm];
        const auto& b = bp[(sgm + 1) % bp.size()];
        double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
        if (l2 == 0) continue;
        double t = std::clamp(((pmsh.points[2 * v] - a.x) * ex + (pmsh.points[2 * v + 1] - a.y) * ey) / l2, 0.0, 1.0);
        double d = std::hypot(a.x + t * ex - pmsh.points[2 * v], a.y + t * ey - pmsh.points[2 * v + 1]);
        if (d < best) best = d, bs = sgm, bt = t;
      }
      w.localToGlobal[v] = addSplitSample(w, bp, bs, bt);
      continue;
    }
    PullbackPoint q;
    if (!pb.locate(pmsh.points[2 * v], pmsh.points[2 * v + 1], q, 1e-6))
      fail(Code::NumericalFailure, Stage::Lift, "a refinement vertex lies outside the flattened patch");
    w.interiorPositions[v] = {q.position[0], q.position[1], q.position[2]};
  }
  w.triangles = pmsh.triangles;
  w.planarPoints = pmsh.points;
  liftSeconds_ += elapsed(tl);
}

// Insert the curve samples a neighbour added on this patch's boundary into its planar mesh:
// split the boundary triangle at the sample, then restore the Delaunay property by Lawson flips
// of interior edges. Positions of existing vertices do not change.
void Pipeline::patchUp(uint32_t p) {
  PatchWork& w = *work_[p];
  w.dirty = false;
  std::vector<BoundaryPoint> bp = boundaryPoints(w);
  auto& P = w.planarPoints;
  auto& T = w.triangles;
  auto edgeKey = [](uint32_t a, uint32_t b) { return (uint64_t(std::min(a, b)) << 32) | std::max(a, b); };
  // boundary edges of the current planar mesh, as directed (a, b) with the opposite vertex
  auto boundaryEdges = [&]() {
    std::unordered_map<uint64_t, int> count;
    for (size_t t = 0; t < T.size(); t += 3)
      for (int c = 0; c < 3; ++c) ++count[edgeKey(T[t + c], T[t + (c + 1) % 3])];
    std::vector<std::array<uint32_t, 2>> out;  // (triangle, corner)
    for (size_t t = 0; t < T.size(); t += 3)
      for (int c = 0; c < 3; ++c)
        if (count[edgeKey(T[t + c], T[t + (c + 1) % 3])] == 1) out.push_back({uint32_t(t / 3), uint32_t(c)});
    return out;
  };
  auto be = boundaryEdges();
  std::vector<uint32_t> touched;
  // samples the mesh already has on its boundary (a seam curve has them twice)
  std::unordered_map<uint32_t, int> have, want;
  for (const auto& e : be) ++have[w.localToGlobal[T[3 * e[0] + e[1]]]];
  for (const auto& b : bp) ++want[b.sample];
  for (const auto& b : bp) {
    if (have[b.sample] >= want[b.sample]) continue;
    ++have[b.sample];
    // the boundary edge it lies on: smallest distance, strictly inside
    double best = INFINITY;
    size_t bi = kNone;
    for (size_t k = 0; k < be.size(); ++k) {
      uint32_t a = T[3 * be[k][0] + be[k][1]], c = T[3 * be[k][0] + (be[k][1] + 1) % 3];
      double ex = P[2 * c] - P[2 * a], ey = P[2 * c + 1] - P[2 * a + 1];
      double l2 = ex * ex + ey * ey;
      if (l2 == 0) continue;
      if (w.localToGlobal[a] == b.sample || w.localToGlobal[c] == b.sample) continue;
      double t = std::clamp(((b.x - P[2 * a]) * ex + (b.y - P[2 * a + 1]) * ey) / l2, 0.0, 1.0);
      double d = std::hypot(P[2 * a] + t * ex - b.x, P[2 * a + 1] + t * ey - b.y);
      if (d < best) best = d, bi = k;
    }
    if (bi == kNone) fail(Code::InternalError, Stage::Stitch, "a shared curve sample is not on the patch boundary");
    uint32_t tri = be[bi][0], c = be[bi][1];
    uint32_t a = T[3 * tri + c], bb = T[3 * tri + (c + 1) % 3], o = T[3 * tri + (c + 2) % 3];
    uint32_t m = uint32_t(P.size() / 2);
    P.insert(P.end(), {b.x, b.y});
    w.localToGlobal.push_back(b.sample);
    w.interiorPositions.push_back({});
    T[3 * tri] = a, T[3 * tri + 1] = m, T[3 * tri + 2] = o;
    uint32_t nt = uint32_t(T.size() / 3);
    T.insert(T.end(), {m, bb, o});
    be[bi] = {tri, 0};
    be.push_back({nt, 0});
    touched.push_back(tri);
    touched.push_back(nt);
  }
  if (touched.empty()) return;
  // Lawson flips on interior edges around the touched triangles
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> adj;
  auto rebuild = [&]() {
    adj.clear();
    for (uint32_t t = 0; t < T.size() / 3; ++t)
      for (int c = 0; c < 3; ++c) {
        auto& x = adj.try_emplace(edgeKey(T[3 * t + c], T[3 * t + (c + 1) % 3]), std::array<uint32_t, 2>{kNone, kNone}).first->second;
        (x[0] == kNone ? x[0] : x[1]) = t;
      }
  };
  rebuild();
  auto incircle = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    double adx = P[2 * a] - P[2 * d], ady = P[2 * a + 1] - P[2 * d + 1];
    double bdx = P[2 * b] - P[2 * d], bdy = P[2 * b + 1] - P[2 * d + 1];
    double cdx = P[2 * c] - P[2 * d], cdy = P[2 * c + 1] - P[2 * d + 1];
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
  };
  auto orient = [&](uint32_t a, uint32_t b, uint32_t c) {
    return (P[2 * b] - P[2 * a]) * (P[2 * c + 1] - P[2 * a + 1]) - (P[2 * b + 1] - P[2 * a + 1]) * (P[2 * c] - P[2 * a]);
  };
  std::vector<uint32_t> stack = touched;
  for (size_t guard = 0; !stack.empty() && guard < 100000; ++guard) {
    uint32_t t = stack.back();
    stack.pop_back();
    for (int c = 0; c < 3; ++c) {
      uint32_t a = T[3 * t + c], b = T[3 * t + (c + 1) % 3], o = T[3 * t + (c + 2) % 3];
      auto it = adj.find(edgeKey(a, b));
      if (it == adj.end() || it->second[1] == kNone) continue;  // boundary edge: constrained
      uint32_t u = it->second[0] == t ? it->second[1] : it->second[0];
      uint32_t d = kNone;
      for (int k = 0; k < 3; ++k)
        if (T[3 * u + k] != a && T[3 * u + k] != b) d = T[3 * u + k];
      if (incircle(a, b, o, d) <= 0) continue;
      // quad strictly convex (relative tolerance: never create a sliver from collinear points)
      double l2 = std::pow(P[2 * o] - P[2 * d], 2) + std::pow(P[2 * o + 1] - P[2 * d + 1], 2);
      double l2ab = std::pow(P[2 * a] - P[2 * b], 2) + std::pow(P[2 * a + 1] - P[2 * b + 1], 2);
      if (orient(o, a, d) <= 1e-10 * std::max(l2, l2ab) || orient(d, b, o) <= 1e-10 * std::max(l2, l2ab)) continue;
      // flip ab -> od: triangles (o, a, d) and (d, b, o), both counter-clockwise
      T[3 * t] = o, T[3 * t + 1] = a, T[3 * t + 2] = d;
      T[3 * u] = d, T[3 * u + 1] = b, T[3 * u + 2] = o;
      rebuild();
      stack.push_back(t);
      stack.push_back(u);
      break;
    }
  }
}

MeshBuffers Pipeline::stitch(std::vector<uint32_t>& trianglePatch) const {
  MeshBuffers out;
  const size_t nS = cm_.samples.size();
  for (const auto& s : cm_.samples) out.positions.insert(out.positions.end(), {s.position.x, s.position.y, s.position.z});
  trianglePatch.clear();
  for (uint32_t p = 0; p < work_.size(); ++p) {
    const PatchWork& w = *work_[p];
    std::vector<uint32_t> id(w.localToGlobal.size());
    for (size_t v = 0; v < id.size(); ++v) {
      if (w.localToGlobal[v] != kNone) id[v] = w.localToGlobal[v];
      else {
        id[v] = uint32_t(out.positions.size() / 3);
        const auto& q = w.interiorPositions[v];
        out.positions.insert(out.positions.end(), {q.x, q.y, q.z});
      }
    }
    for (size_t t = 0; t < w.triangles.size(); t += 3) {
      out.triangles.insert(out.triangles.end(), {id[w.triangles[t]], id[w.triangles[t + 1]], id[w.triangles[t + 2]]});
      trianglePatch.push_back(p);
    }
  }
  (void)nS;
  return out;
}

double triangleMinAngle(const MeshBuffers& m, size_t t, double* maxAngle = nullptr) {
  F::Vec3 p[3];
  for (int c = 0; c < 3; ++c) {
    uint32_t v = m.triangles[3 * t + c];
    p[c] = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
  }
  double lo = INFINITY, hi = 0;
  for (int c = 0; c < 3; ++c) {
    double a = F::angleBetween(p[(c + 1) % 3] - p[c], p[(c + 2) % 3] - p[c]) * 180.0 / kPi;
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  if (maxAngle) *maxAngle = hi;
  return lo;
}

RemeshResult Pipeline::run(const MeshBuffers& input) {
  RemeshResult res;
  auto t0 = std::chrono::steady_clock::now(), tStart = t0;
  if (!(opt_.minAngleDeg >= 0 && opt_.minAngleDeg <= 34))
    fail(Code::InvalidArgument, Stage::Api, "minAngle must be in [0, 34] degrees");
  if (!(opt_.maxScaleRatio > 1)) fail(Code::InvalidArgument, Stage::Api, "maxScaleRatio must be > 1");
  checkCancel(Stage::Validate, 0);
  ValidatedMesh vm = validate(input);
  const MeshBuffers& in = vm.buffers;
  rep_.inputTriangles = in.triangleCount();
  rep_.inputVertices = in.vertexCount();
  for (const auto& wn : vm.report.warnings) rep_.warnings.push_back(wn.message);
  rep_.seconds.validate = elapsed(t0);

  checkCancel(Stage::Segment, 0);
  g_ = F::buildEdgeGraph(in);
  F::FeatureOptions fo;
  fo.featureAngleDeg = opt_.featureAngleDeg;
  fo.cornerTurnDeg = opt_.cornerTurnDeg;
  for (const auto& e : opt_.featureEdges) {
    if (e[0] >= vm.inputToVertex.size() || e[1] >= vm.inputToVertex.size())
      fail(Code::InvalidArgument, Stage::Segment, "a feature edge refers to a vertex out of range");
    fo.featureEdges.push_back({vm.inputToVertex[e[0]], vm.inputToVertex[e[1]]});
  }
  seg_ = F::segment(g_, fo, progress_);
  F::SizingOptions so;
  so.targetEdgeLength = opt_.targetEdgeLength;
  so.targetEdgeLengthRel = opt_.targetEdgeLengthRel;
  so.chordTolerance = opt_.chordTolerance;
  so.chordToleranceRel = opt_.chordToleranceRel;
  so.gradation = opt_.gradation;
  so.minEdgeLength = opt_.minEdgeLength;
  so.maxEdgeLength = opt_.maxEdgeLength;
  if (!opt_.vertexSizing.empty()) {
    if (opt_.vertexSizing.size() != input.vertexCount())
      fail(Code::InvalidArgument, Stage::CurveMesh, "vertexSizing needs one value per input vertex");
    so.vertexSizing.resize(in.vertexCount());
    for (size_t v = 0; v < so.vertexSizing.size(); ++v) so.vertexSizing[v] = opt_.vertexSizing[vm.vertexToInput[v]];
  }
  sizing_ = F::computeSizing(g_, seg_, so);
  {  // output size and memory limits, before the heavy work (remesh/limits.h)
    const OutputEstimate est = estimateOutput(g_, sizing_);
    rep_.estimatedTriangles = est.triangles;
    checkOutputEstimate(est, opt_);
  }
  rep_.targetEdgeLength = sizing_.target;
  rep_.seconds.segment = elapsed(t0);

  checkCancel(Stage::Flatten, 0);
  flattenPatches();
  rep_.seconds.flatten = elapsed(t0);

  checkCancel(Stage::CurveMesh, 0);
  cm_ = F::sampleCurves(g_, seg_, sizing_);
  indexSamples();
  rep_.seconds.curveMesh = elapsed(t0);

  // refine + lift, re-meshing neighbours of split segments, then the 3D angle certificate
  MeshBuffers out;
  std::vector<uint32_t> triPatch;
  std::vector<uint8_t> exemptVertex;
  MeshBuffers bestOut;
  std::vector<uint32_t> bestTriPatch;
  size_t bestBad = SIZE_MAX;
  std::vector<std::vector<uint32_t>> bestCurveSamples;
  for (int cert = 0;; ++cert) {
    int round = 0;
    {
      std::vector<uint32_t> todo;
      for (uint32_t p = 0; p < work_.size(); ++p)
        if (work_[p]->needsMesh) todo.push_back(p);
      for (size_t i = 0; i < todo.size(); ++i) {
        meshPatch(todo[i]);
        checkCancel(Stage::Refine, double(i + 1) / double(todo.size()));
      }
      // patches whose boundary got samples from a neighbour's segment splits: insert them
      // (boundary edge split + Delaunay flips); this adds no new samples, so one pass suffices
      for (uint32_t p = 0; p < work_.size(); ++p)
        if (work_[p]->dirty) patchUp(p), round = 1;
    }
    rep_.conformingRounds = std::max(rep_.conformingRounds, round);
    rep_.seconds.refine += elapsed(t0);
    out = stitch(triPatch);
    // exempt corners: input corners whose angle inside some patch is below the bound
    if (exemptVertex.empty()) {
      exemptVertex.assign(out.vertexCount(), 0);
      rep_.exemptCorners.clear();
      for (uint32_t p = 0; p < work_.size(); ++p) {
        const auto& pm = work_[p]->pm;
        std::vector<double> ang = cornerWedgeAngles(pm);
        for (uint32_t v = 0; v < pm.vertexInput.size(); ++v) {
          uint32_t iv = pm.vertexInput[v];
          if (!seg_.vertexCorner[iv] || ang[v] * 180.0 / kPi >= opt_.minAngleDeg) continue;
          uint32_t s = cm_.cornerSample[iv];
          if (s == kNone || exemptVertex[s]) continue;
          exemptVertex[s] = 1;
          rep_.exemptCorners.push_back({vm.vertexToInput[iv], s, ang[v] * 180.0 / kPi, {}});
        }
      }
    }
    exemptVertex.resize(out.vertexCount(), 0);
    size_t bad = 0;
    for (size_t t = 0; t < out.triangleCount(); ++t) {
      const uint32_t* tv = &out.triangles[3 * t];
      if (!exemptVertex[tv[0]] && !exemptVertex[tv[1]] && !exemptVertex[tv[2]] && triangleMinAngle(out, t) < opt_.minAngleDeg)
        ++bad;
    }
    if (std::getenv("CONFORMESH_DEBUG2")) std::fprintf(stderr, "certificate round %d: %zu bad triangles of %zu\n", cert, bad, out.triangleCount());
    if (bad < bestBad) {
      bestBad = bad;
      bestOut = out;
      bestTriPatch = triPatch;
      bestCurveSamples = cm_.curveSamples;
    } else {
      // refining made it worse (a boundary-condition corner whose planar and 3D angles differ
      // cannot be fixed by size): keep the best round
      break;
    }
    if (bad == 0 || cert >= opt_.maxCertificateRounds) break;
    // 3D angle certificate: where a lifted triangle is below the bound, ask for smaller planar
    // triangles there (a graded spot at its planar centroid) and re-mesh the patch.
    std::vector<size_t> firstTri(work_.size(), 0);
    for (size_t i = triPatch.size(); i-- > 0;) firstTri[triPatch[i]] = i;
    for (size_t t = 0; t < out.triangleCount(); ++t) {
      if (triangleMinAngle(out, t) >= opt_.minAngleDeg) continue;
      const uint32_t* tv = &out.triangles[3 * t];
      if (exemptVertex[tv[0]] || exemptVertex[tv[1]] || exemptVertex[tv[2]]) continue;
      PatchWork& w = *work_[triPatch[t]];
      const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
      double cx = 0, cy = 0, longest = 0;
      for (int c = 0; c < 3; ++c) {
        cx += w.planarPoints[2 * lt[c]] / 3.0;
        cy += w.planarPoints[2 * lt[c] + 1] / 3.0;
        uint32_t a = lt[c], b = lt[(c + 1) % 3];
        longest = std::max(longest, std::hypot(w.planarPoints[2 * a] - w.planarPoints[2 * b],
                                               w.planarPoints[2 * a + 1] - w.planarPoints[2 * b + 1]));
      }
      w.spots.push_back({cx, cy, 0.5 * longest});
      w.needsMesh = true;
    }
    ++rep_.certificateRounds;
  }
  out = std::move(bestOut);
  triPatch = std::move(bestTriPatch);
  cm_.curveSamples = std::move(bestCurveSamples);
  rep_.seconds.lift = liftSeconds_;
  rep_.seconds.refine -= liftSeconds_;
  rep_.seconds.stitch = elapsed(t0);
  checkOutputCounts(out.vertexCount(), out.triangleCount(), opt_);  // remesh/limits.h

  // report
  auto as = quality::angleStats(out);
  rep_.triangles = out.triangleCount();
  rep_.vertices = out.vertexCount();
  rep_.minAngle = as.minAngle;
  rep_.maxAngle = as.maxAngle;
  rep_.meanMinAngle = as.meanMinAngle;
  rep_.pctBelow20 = as.pctBelow20;
  rep_.pctBelow26 = as.pctBelow26;
  rep_.pctBelow30 = as.pctBelow30;
  rep_.minAngleOutsideExempt = 180;
  for (size_t t = 0; t < out.triangleCount(); ++t) {
    const uint32_t* tv = &out.triangles[3 * t];
    bool ex = false;
    for (int c = 0; c < 3; ++c)
      if (exemptVertex[tv[c]]) {
        ex = true;
        for (auto& ec : rep_.exemptCorners)
          if (ec.outputVertex == tv[c]) ec.triangles.push_back(uint32_t(t));
      }
    if (ex) continue;
    double a = triangleMinAngle(out, t);
    rep_.minAngleOutsideExempt = std::min(rep_.minAngleOutsideExempt, a);
    if (a < opt_.minAngleDeg) ++rep_.trianglesBelowBoundOutsideExempt;
  }
  auto es = quality::edgeStats(out);
  rep_.meanEdgeLength = es.meanLength;
  rep_.delaunayFraction = es.delaunayFraction;
  auto ti = quality::topologySummary(in), to = quality::topologySummary(out);
  rep_.topologyPreserved = ti.components == to.components && ti.boundaryLoops == to.boundaryLoops &&
                           ti.genus == to.genus && to.nonManifoldEdges == 0;
  // feature curves kept: every pair of consecutive samples is an output edge
  std::unordered_set<uint64_t> edges;
  for (size_t t = 0; t < out.triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      uint64_t a = out.triangles[t + c], b = out.triangles[t + (c + 1) % 3];
      edges.insert(std::min(a, b) << 32 | std::max(a, b));
    }
  for (size_t c = 0; c < seg_.curves.size(); ++c) {
    if (seg_.curves[c].kind == F::EdgeKind::Cut) continue;
    ++rep_.featureCurves;
    bool kept = true;
    const auto& ids = cm_.curveSamples[c];
    for (size_t i = 0; i + 1 < ids.size() && kept; ++i) {
      uint64_t a = ids[i], b = ids[i + 1];
      kept = edges.count(std::min(a, b) << 32 | std::max(a, b)) > 0;
      if (!kept && std::getenv("CONFORMESH_DEBUG2"))
        std::fprintf(stderr, "curve %zu (%zu samples): pair %zu (%u, %u) keys %g %g not an edge\n", c, ids.size(), i, ids[i], ids[i + 1], curveKey(uint32_t(c), ids[i]), curveKey(uint32_t(c), ids[i + 1]));
    }
    rep_.featureCurvesKept += kept;
  }
  rep_.sharpEdges = seg_.sharpEdgeCount;
  rep_.cutEdges = seg_.cutEdgeCount;
  rep_.patches = work_.size();
  rep_.curves = seg_.curves.size();
  rep_.curveSamples = cm_.samples.size();
  rep_.patchSplitsForScale = scaleSplits_;
  for (const auto& w : work_) rep_.flowIterations.push_back(w->flat.report.iterations);
  {
    quality::TriangleMeshDistance dist(in);
    double worst = 0;
    for (size_t v = 0; v < out.vertexCount(); ++v) {
      auto hit = dist.closest({out.positions[3 * v], out.positions[3 * v + 1], out.positions[3 * v + 2]});
      worst = std::max(worst, hit.distanceSquared);
    }
    rep_.maxDistanceToInputRel = std::sqrt(worst) / sizing_.diagonal;
  }
  if (opt_.computeHausdorff) {
    quality::HausdorffOptions ho;
    ho.samplesPerSide = opt_.hausdorffSamples;
    rep_.hausdorffRel = quality::hausdorffDistance(out, in, ho).relative;
  }
  checkCancel(Stage::Report, 1.0);
  rep_.seconds.report = elapsed(t0);
  rep_.seconds.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - tStart).count();
  res.mesh = std::move(out);
  res.report = rep_;
  return res;
}

}  // namespace

RemeshResult remesh(const MeshBuffers& input, const RemeshOptions& options, ProgressFn progress) {
  RemeshResult r;
  try {
    Pipeline p(options, progress);
    r = p.run(input);
  } catch (const Error& e) {
    r = RemeshResult{};
    r.status = e.status();
  } catch (const std::bad_alloc&) {
    r = RemeshResult{};
    r.status = Status{Code::TooLarge, Stage::Api, "out of memory"};
  } catch (const std::exception& e) {
    r = RemeshResult{};
    r.status = Status{Code::InternalError, Stage::Api, e.what()};
  }
  return r;
}

}  // namespace conformesh
