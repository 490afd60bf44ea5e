#include "remesh/remesh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <unordered_map>

#include "conformal/flatten.h"
#include "features/curve_mesh.h"
#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "mesh/validate.h"
#include "planar/predicates.h"
#include "planar/refine.h"
#include "quality/metrics.h"
#include "mesh/mesh_attributes.h"
#include "mesh/precondition.h"
#include "remesh/carry_attributes.h"
#include "remesh/optimize.h"
#include "remesh/repair.h"
#include "remesh/spot_field.h"
#include "remesh/stitch_defects.h"
#include "remesh/limits.h"
#include "core/detmath.h"
#include "core/hilbert.h"
#include "core/vertex_stars.h"

namespace conformesh {
namespace {

namespace F = features;

//! x² as one product (std::pow(x, 2) goes through libm in some builds).
inline double sq(double x) { return x * x; }
using F::kNone;
constexpr double kPi = 3.14159265358979323846;
// Rounds of re-refining patches whose boundary got samples from a neighbour's segment splits.
constexpr int kConformingRounds = 8;
// Patches with fewer input faces are not split further. A single triangle always develops
// isometrically, so splitting down to small patches beats the round-disk fallback, whose
// distortion on a small curved patch leaves triangles below the bound (docs/decisions/0009).
constexpr size_t kMinSplitFaces = 2;
// Degrees added to the angle bound for the planar refinement (see meshPatch).
constexpr double kPlanarAngleMargin = 2.0;
// Angle (degrees) at the new vertex of the triangle an off-center (Üngör 2009) makes with the
// shortest edge of a bad triangle: halfway between the bound and equilateral, so graded bands do
// not stay at the bound, while the new vertex stays 1.3 edges away and insertion radii still grow
// (docs/decisions/0012-offcenter-apex.md).
constexpr double kOffcenterApexDeg = 45.0;
// Passes of the last repair over the triangles still below the bound (a hard cap; a pass that
// moves nothing ends it). Each pass moves a vertex by a fraction of its star at most, and making
// room takes a few passes.
constexpr int kRepairRounds = 32;
// Shortest boundary piece a patch refinement may split, in the sizing's smallest edge length
// (minEdgeLength, target/10 by default), on the surface: far below any size the output can mean.
// Near a small angle between two curves the refinements of the two sides can keep splitting
// each other's segments (each side's concentric shells are not the other's) down to 1e-9 of the
// diagonal, every new triangle there below the bound (docs/decisions/0002).
constexpr double kMinSegmentFactor = 1e-2;
// Two splits of one input edge closer than this (in target edge lengths) are one sample.
constexpr double kSameSampleFactor = 1e-9;
// Default minFeatureLength in target edge lengths: a chain of sharp edges shorter than two
// output edges gets at most one sample inside, too few to carry a feature; on scans such chains
// are bumps of the noise, and each one needs cuts to join the rest (docs/decisions/0006).
constexpr double kMinFeatureFactor = 2.0;
// Times a patch's boundary chords may be split where they cross before refinement gives up.
constexpr int kCrossingRepairs = 8;
// Certificate rounds past the cap for a stitch defect still there, with its patches keeping their
// boundary (one opened it in every case measured; the second is a margin).
constexpr int kKeepBoundaryRounds = 2;
// The last repair may move a star this fraction of the chord tolerance from the input (besides
// as far as it was; remesh/repair.h): 2.5e-4 of the diagonal by default, below the output's
// distance to the input elsewhere (~1e-3; docs/decisions/0013).
constexpr double kRepairDeviationFloor = 0.25;
// Input edges longer than this times the target edge length are split before segmentation, so
// cuts along input edges are not sawtooths of needle edges (mesh/precondition.h).
constexpr double kPreconditionEdgeFactor = 2.0;

// Vertex v of m becomes vertex id[v] (kNone: dropped) of a mesh with `count` vertices; the
// triangles and edges follow.
void renumberVertices(planar::PlanarMesh& m, const std::vector<uint32_t>& id, size_t count) {
  std::vector<double> points(2 * count), param(count);
  std::vector<int32_t> segment(count);
  for (size_t v = 0; v < id.size(); ++v) {
    if (id[v] == kNone) continue;
    points[2 * size_t(id[v])] = m.points[2 * v];
    points[2 * size_t(id[v]) + 1] = m.points[2 * v + 1];
    segment[id[v]] = m.vertexSegment[v];
    param[id[v]] = m.vertexParam[v];
  }
  m.points.swap(points);
  m.vertexSegment.swap(segment);
  m.vertexParam.swap(param);
  for (uint32_t& v : m.triangles) v = id[v];
  for (uint32_t& v : m.edges) v = id[v];
}

// Remove the vertices from index `keep` on that no triangle uses (a required point that a later
// boundary split left outside the domain, or one inserted twice), renumbering the rest: every
// vertex of a patch's meshing becomes an output vertex.
void dropUnusedPoints(planar::PlanarMesh& m, size_t keep) {
  const size_t nv = m.vertexCount();
  std::vector<uint32_t> id(nv, kNone);
  for (uint32_t v : m.triangles) id[v] = 0;
  size_t next = 0;
  bool any = false;
  for (size_t v = 0; v < nv; ++v) {
    if (v < keep || id[v] == 0) id[v] = uint32_t(next++);
    else any = true;
  }
  if (any) renumberVertices(m, id, next);
}

// Renumber the vertices from index `keep` on along a Hilbert curve over their planar positions,
// and order the triangles by their smallest vertex (then the others): the refinement leaves them
// in the order its queue inserted them, all over the patch, while the lift, the optimization and
// the certificate visit vertices by index and a vertex's star by its triangles. Neighbours in
// memory are then neighbours in the plane (the optimization's stars, lifts and guard).
void spatialOrder(planar::PlanarMesh& m, size_t keep) {
  const size_t nv = m.vertexCount();
  if (nv <= keep + 1) return;
  std::vector<uint32_t> refined(nv - keep);
  std::iota(refined.begin(), refined.end(), uint32_t(keep));
  const std::vector<uint32_t> order = hilbertOrder(m.points.data(), refined);
  std::vector<uint32_t> id(nv);
  for (size_t v = 0; v < keep; ++v) id[v] = uint32_t(v);
  for (size_t i = 0; i < order.size(); ++i) id[order[i]] = uint32_t(keep + i);
  renumberVertices(m, id, nv);
  // triangles: rotated to start at their smallest vertex (orientation kept), then sorted
  const size_t nt = m.triangleCount();
  std::vector<std::array<uint32_t, 3>> tris(nt);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* x = &m.triangles[3 * t];
    const int r = x[0] <= x[1] && x[0] <= x[2] ? 0 : (x[1] <= x[2] ? 1 : 2);
    tris[t] = {x[r], x[(r + 1) % 3], x[(r + 2) % 3]};
  }
  std::sort(tris.begin(), tris.end());
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) m.triangles[3 * t + k] = tris[t][k];
}

// Largest distance of a patch's input vertices from the plane through their centroid normal to
// the patch's area-weighted normal (infinity when that normal vanishes: a closed-up patch).
double slabHalfWidth(const F::PatchMesh& pm) {
  const auto& P = pm.mesh.positions;
  const size_t nv = pm.mesh.vertexCount();
  if (nv == 0) return INFINITY;
  const auto at = [&](uint32_t v) { return F::Vec3{P[3 * size_t(v)], P[3 * size_t(v) + 1], P[3 * size_t(v) + 2]}; };
  F::Vec3 n{0, 0, 0}, c{0, 0, 0};
  for (size_t t = 0; t < pm.mesh.triangleCount(); ++t) {
    const uint32_t* v = &pm.mesh.triangles[3 * t];
    n = n + F::cross(at(v[1]) - at(v[0]), at(v[2]) - at(v[0]));
  }
  for (uint32_t v = 0; v < nv; ++v) c = c + at(v);
  c = c * (1.0 / double(nv));
  const double ln = F::norm(n);
  if (!(ln > 0)) return INFINITY;
  n = n * (1.0 / ln);
  double w = 0;
  for (uint32_t v = 0; v < nv; ++v) w = std::max(w, std::abs(F::dot(n, at(v) - c)));
  return std::isfinite(w) ? w : INFINITY;
}

double elapsed(std::chrono::steady_clock::time_point& t) {
  auto now = std::chrono::steady_clock::now();
  double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

// A spot where the 3D angle certificate asks for smaller planar triangles: h <= h0 + |x − c|/2.
// One patch: its sub-mesh, flattening, boundary condition, sizing, and its latest meshing.
struct PatchWork {
  F::PatchMesh pm;
  FlatPatch flat;
  std::vector<double> hSub;      // 3D target length per sub vertex
  std::vector<double> scaleSub;  // planar length per 3D length, per sub vertex
  std::vector<Spot> spots;
  std::vector<double> requiredPoints;  // planar points every refinement of the patch must contain
  // latest meshing
  std::vector<uint32_t> localToGlobal;  // planar vertex -> output vertex (samples first)
  std::vector<F::Vec3> interiorPositions;  // positions of planar vertices that are interior
  std::vector<int> layoutFaces;             // per planar vertex: the flattened face of its lift, -1 none
  std::vector<uint32_t> liftFaces;          // per planar vertex: the input (g_) face of its latest lift, kNone none
  optimization::OptimizeCache optimizeCache;  // the latest optimizePatch's, for the next one on this meshing
  std::vector<uint32_t> triangles;         // planar triangles (local indices)
  std::vector<double> planarPoints;        // planar positions of the latest meshing
  uint64_t builtAt = 0;
  bool needsMesh = true;  // full refinement (first time, or the certificate asked for spots)
  bool dirty = false;     // a neighbour added curve samples on this patch's boundary
  bool optimized = false;  // the latest meshing went through optimizePatch
  // refine without splitting the boundary: a stitch defect (a corner wedge both patches close
  // with one triangle, a chord both have) is still there at the certificate's cap. The splits a
  // required point inside it causes on the wedge's sides usually open it with good angles within
  // a few rounds, but they can also close it again closer to the corner every time
  bool keepBoundary = false;
  double slabHalfWidth = -1;  // largest distance of the patch's input vertices from their mean plane (-1: not yet known)

};

// A piece of the patch's boundary polyline: boundary halfedge k of the loop, from parameter t0
// to t1 along it.
struct Piece {
  uint32_t k;
  double t0, t1;
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
  void flattenPatches();
  std::vector<std::pair<uint32_t, double>> boundaryCorners(const F::PatchMesh& pm) const;
  void indexSamples();
  std::vector<BoundaryPoint> boundaryPoints(const PatchWork& w) const;
  void meshPatch(uint32_t p, bool splitSegments = true);
  void optimizeMesh(uint32_t p, const std::vector<uint8_t>& active = {});
  std::vector<std::vector<uint8_t>> slideSamples();
  bool liftPoint(const PatchWork& w, double x, double y, PullbackPoint& q, int hintFace = -1) const;
  std::vector<Piece> stretch(const PatchWork& w, const BoundaryPoint& p0, const BoundaryPoint& p1, size_t points) const;
  uint32_t addSplitSample(const PatchWork& w, const std::vector<BoundaryPoint>& bp, uint32_t s, double t);
  double curveKey(uint32_t c, uint32_t sample) const;
  MeshBuffers stitch(std::vector<uint32_t>& trianglePatch, std::vector<uint32_t>& vertexFace) const;
  std::vector<RemeshPatch> patchSnapshot(const MeshBuffers& out) const;
  std::vector<double> cornerWedgeAngles(const F::PatchMesh& pm) const;
  void indexExemptWedges(const std::vector<uint8_t>& exemptVertex);
  uint32_t exemptCornerOf(const MeshBuffers& out, size_t t, const std::vector<uint8_t>& exemptVertex) const;

  const RemeshOptions& opt_;
  const ProgressFn& progress_;
  Preconditioned pre_;  // the input after mesh/precondition.h (the first vertices are the input's)
  // The chord tolerance in the input's units (the sizing's, features/sizing.h).
  double chordTolerance() const { return opt_.chordTolerance >= 0 ? opt_.chordTolerance : opt_.chordToleranceRel * sizing_.diagonal; }
  F::EdgeGraph g_;
  const MeshBuffers* graphMesh_ = nullptr;  // the mesh g_ was built from (same vertex and face indices)
  F::Segmentation seg_;
  F::SizingField sizing_;
  F::CurveMesh cm_;
  std::vector<std::unique_ptr<PatchWork>> work_;
  std::vector<std::vector<uint32_t>> edgeSamples_;  // interior samples per input edge
  std::vector<uint32_t> vertexSample_;              // sample at an input vertex
  std::vector<uint32_t> edgeIndexInCurve_;
  // per curve sample: (exempt corner sample, curve) for each curve through it that ends at an
  // exempt corner
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> wedgeCurves_;
  std::unordered_map<uint32_t, double> exemptWedgeDeg_;  // exempt corner sample -> its wedge angle
  uint64_t stamp_ = 0;
  size_t scaleSplits_ = 0;
  double liftSeconds_ = 0;
  double optimizeSeconds_ = 0;
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

void Pipeline::indexExemptWedges(const std::vector<uint8_t>& exemptVertex) {
  wedgeCurves_.assign(cm_.samples.size(), {});
  for (uint32_t c = 0; c < seg_.curves.size(); ++c) {
    const auto& ids = cm_.curveSamples[c];
    for (uint32_t corner : {ids.front(), ids.back()}) {
      if (corner >= exemptVertex.size() || !exemptVertex[corner]) continue;
      for (uint32_t s : ids)
        if (s != corner) wedgeCurves_[s].push_back({corner, c});
      if (ids.front() == ids.back()) break;  // a closed curve: once
    }
  }
}

// The exempt corner triangle t belongs to, or kNone: it touches the corner, or one of its edges
// spans the corner's small wedge: its ends lie on two different curves that meet at the corner,
// at distances from it within a factor 2 of each other, and it is seen from the corner under an
// angle between half the corner's wedge angle and the bound. Ruppert's concentric shells leave
// such skinny triangles there, whose angle the input forces (the "seditious edges" of Shewchuk
// 2002). Where the two curves stop diverging (a long strip between them), an edge across is
// seen under less and less: not exempt.
uint32_t Pipeline::exemptCornerOf(const MeshBuffers& out, size_t t, const std::vector<uint8_t>& exemptVertex) const {
  const uint32_t* tv = &out.triangles[3 * t];
  for (int c = 0; c < 3; ++c)
    if (exemptVertex[tv[c]]) return tv[c];
  auto pos = [&](uint32_t v) { return F::Vec3{out.positions[3 * v], out.positions[3 * v + 1], out.positions[3 * v + 2]}; };
  for (int c = 0; c < 3; ++c) {
    const uint32_t a = tv[c], b = tv[(c + 1) % 3];
    if (a >= wedgeCurves_.size() || b >= wedgeCurves_.size()) continue;
    for (const auto& [ca, cua] : wedgeCurves_[a])
      for (const auto& [cb, cub] : wedgeCurves_[b]) {
        if (ca != cb || cua == cub) continue;
        const F::Vec3 p = pos(ca), da = pos(a) - p, db = pos(b) - p;
        const double la = F::norm(da), lb = F::norm(db), seen = F::angleBetween(da, db) * 180.0 / kPi;
        if (la <= 2 * lb && lb <= 2 * la && seen < opt_.minAngleDeg && seen >= 0.5 * exemptWedgeDeg_.at(ca)) return ca;
      }
  }
  return kNone;
}

// Corners for the corner-preserving boundary condition (the fallback when the free boundary
// overlaps itself): boundary wedges at curve corners whose 3D angle differs from π by more than
// 10°, each with its own 3D angle as target; the flow spreads the rest of the boundary turning
// (2π − Σ(π − α)) along the sides by arc length, so the sides bend instead of the corners.
std::vector<std::pair<uint32_t, double>> Pipeline::boundaryCorners(const F::PatchMesh& pm) const {
  std::vector<double> angle = cornerWedgeAngles(pm);
  std::vector<uint8_t> onBoundary(pm.vertexInput.size(), 0);
  for (const auto& h : pm.boundaryLoops[0]) onBoundary[pm.mesh.triangles[3 * h.face + h.corner]] = 1;
  std::vector<std::pair<uint32_t, double>> out;
  for (uint32_t v = 0; v < pm.vertexInput.size(); ++v) {
    if (!onBoundary[v] || !seg_.vertexCorner[pm.vertexInput[v]]) continue;
    if (std::abs(angle[v] - kPi) < 10.0 * kPi / 180.0) continue;
    out.push_back({v, std::clamp(angle[v], 1e-3, 2 * kPi - 1e-3)});
  }
  return out;
}

void Pipeline::flattenPatches() {
  // flattened patches by their exact face set: splitting a patch can reroute the cuts of its
  // neighbours (improveCutJunctions), which changes their faces and so their flattening
  std::map<std::vector<uint32_t>, std::unique_ptr<PatchWork>> cache;
  auto keyOf = [](std::vector<uint32_t> faces) {
    std::sort(faces.begin(), faces.end());
    return faces;
  };
  // each round flattens what is new and splits at most one patch: the rounds are capped by the
  // patches the segmentation may make (a split that undoes another would otherwise cycle)
  const uint32_t maxPatches = F::FeatureOptions{}.maxPatches;
  for (int round = 0;; ++round) {
    if (round > 64 + 2 * int(maxPatches) || seg_.patches.size() > maxPatches)
      fail(Code::IterationLimit, Stage::Flatten,
           "splitting patches for their scale factor did not settle (" + std::to_string(seg_.patches.size()) + " patches after " +
               std::to_string(round) + " rounds)");
    auto mask = seg_.curveMask();
    bool split = false;
    for (uint32_t p = 0; p < seg_.patches.size() && !split; ++p) {
      const auto& faces = seg_.patches[p];
      auto key = keyOf(faces);
      if (cache.count(key)) continue;
      auto w = std::make_unique<PatchWork>();
      w->pm = F::extractPatch(g_, mask, faces);
      if (!w->pm.isDisk()) fail(Code::InternalError, Stage::Flatten, "a patch is not a disk after cutting");
      // Boundary conditions, least distorting first. Free (u = 0 on the boundary): isometric
      // on developable patches, so planar angles are 3D angles and corners keep theirs; its
      // layout can overlap itself on strongly curved patches. Then corner-preserving (corners
      // keep their 3D angle, the sides bend), then the round disk (always embedded).
      std::vector<BoundaryCondition> order = {opt_.boundary};
      for (BoundaryCondition bc : {BoundaryCondition::Free, BoundaryCondition::Corners, BoundaryCondition::Circle})
        if (bc != opt_.boundary) order.push_back(bc);
      bool flattened = false;
      std::string lastError;
      for (BoundaryCondition bc : order) {
        FlattenOptions fo;
        fo.boundary = bc;
        if (bc == BoundaryCondition::Corners) {
          fo.corners = boundaryCorners(w->pm);
          if (fo.corners.empty()) continue;
        }
        try {
          w->flat = flatten(w->pm.mesh, fo);
          flattened = true;
          if (bc != order.front())
            rep_.warnings.push_back(std::string("patch flattened with the ") +
                                    (bc == BoundaryCondition::Free      ? "free"
                                     : bc == BoundaryCondition::Corners ? "corner-preserving"
                                                                        : "round (circle)") +
                                    " boundary condition after: " + lastError + " [patch of " + std::to_string(faces.size()) + " faces]");
          break;
        } catch (const Error& e) {
          if (e.code() == Code::Cancelled) throw;
          lastError = e.what();
          // the free boundary failed (its layout overlaps itself): smaller parts are closer to
          // developable and keep the least distorting map; split while the patch is big enough
          if (bc == order.front() && faces.size() >= kMinSplitFaces && F::splitPatch(g_, seg_, p)) {
            ++scaleSplits_;
            rep_.warnings.push_back("patch split after its first boundary condition failed: " + lastError);
            split = true;
            break;
          }
        }
      }
      if (split) break;
      if (!flattened) {
        // every boundary condition failed (a layout that overlaps itself or a flow that stalls):
        // split the patch and retry
        if (faces.size() < kMinSplitFaces || !F::splitPatch(g_, seg_, p))
          fail(Code::NumericalFailure, Stage::Flatten, "patch " + std::to_string(p) + " could not be flattened: " + lastError);
        ++scaleSplits_;
        rep_.warnings.push_back("patch split after a flattening failure: " + lastError);
        split = true;
        break;
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
      if (smax > opt_.maxScaleRatio * smin && faces.size() >= kMinSplitFaces) {
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
    for (const auto& faces : seg_.patches) work_.push_back(std::move(cache.at(keyOf(faces))));
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

// The pieces of the boundary polyline from boundary point p0 to the next one, p1 (`points`
// boundary points in all).
std::vector<Piece> Pipeline::stretch(const PatchWork& w, const BoundaryPoint& p0, const BoundaryPoint& p1, size_t points) const {
  const auto& loop = w.pm.boundaryLoops[0];
  std::vector<Piece> pieces;
  uint32_t k = p0.loopPos;
  double from = p0.param;
  for (size_t guard = 0; guard <= loop.size() + 1; ++guard) {
    if (k == p1.loopPos && (p1.param >= from || pieces.size() > 0 || points > 1)) {
      if (!(k == p0.loopPos && pieces.empty() && p1.param < from)) {
        pieces.push_back({k, from, p1.param});
        break;
      }
    }
    pieces.push_back({k, from, 1.0});
    k = (k + 1) % uint32_t(loop.size());
    from = 0.0;
  }
  return pieces;
}

// A refinement vertex inserted on boundary segment s (from boundary point s to s+1) at
// parameter t: find it on the patch boundary polyline in the plane, make it a curve sample on the
// input edge there, and ask the patches on the curve to include it.
uint32_t Pipeline::addSplitSample(const PatchWork& w, const std::vector<BoundaryPoint>& bp, uint32_t s, double t) {
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  const BoundaryPoint& p0 = bp[s];
  const BoundaryPoint& p1 = bp[(s + 1) % bp.size()];
  const std::vector<Piece> pieces = stretch(w, p0, p1, bp.size());
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
    len[i] = dmath::hypot(x1 - x0, y1 - y0);
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
  // A split must add a point strictly inside this stretch, never one of its ends: where it
  // falls on an end (a stretch between two samples closer than the dedupe resolution, as two
  // input corners a rounding error apart give), it goes to the middle of its piece instead.
  const bool onEnd = smp.t <= 0.0 || smp.t >= 1.0;
  const uint32_t endSample = onEnd ? vertexSample_[smp.t <= 0.0 ? g_.edgeVerts[e][0] : g_.edgeVerts[e][1]] : kNone;
  if (onEnd && (endSample == p0.sample || endSample == p1.sample) && pieces[i].t1 > pieces[i].t0) {
    th = 0.5 * (pieces[i].t0 + pieces[i].t1);
    smp.t = g_.edgeVerts[e][0] == A ? th : 1.0 - th;
  }
  if (smp.t <= 0.0 || smp.t >= 1.0) {
    uint32_t v = smp.t <= 0.0 ? g_.edgeVerts[e][0] : g_.edgeVerts[e][1];
    if (vertexSample_[v] != kNone) {
      if (vertexSample_[v] == p0.sample || vertexSample_[v] == p1.sample)
        fail(Code::InternalError, Stage::Refine, "a boundary stretch has no length to split");
      return vertexSample_[v];
    }
    smp.t = smp.t <= 0.0 ? 0.0 : 1.0;
    smp.vertex = v;
  }
  // a seam (a cut with the patch on both sides) is split at the same place from both sides:
  // one sample for both (but never an end of this stretch)
  if (smp.vertex == kNone)
    for (uint32_t o : edgeSamples_[e])
      if (std::abs(cm_.samples[o].t - smp.t) * g_.edgeLength(e) < kSameSampleFactor * sizing_.target &&
          o != p0.sample && o != p1.sample)
        return o;
  smp.position = g_.positions[g_.edgeVerts[e][0]] * (1.0 - smp.t) + g_.positions[g_.edgeVerts[e][1]] * smp.t;
  uint32_t id = uint32_t(cm_.samples.size());
  cm_.samples.push_back(smp);
  if (smp.vertex != kNone) vertexSample_[smp.vertex] = id;
  else edgeSamples_[e].push_back(id);
  uint32_t c = seg_.edgeCurve[e];
  if (c == kNone) fail(Code::InternalError, Stage::Refine, "a patch boundary edge is on no curve");
  auto& ids = cm_.curveSamples[c];
  double key = curveKey(c, id);
  size_t pos = 1;
  while (pos + 1 < ids.size() && curveKey(c, ids[pos]) < key) ++pos;
  ids.insert(ids.begin() + long(pos), id);
  ++stamp_;
  for (uint32_t q : seg_.curves[c].patches)
    if (q != kNone && work_[q]->builtAt < stamp_) work_[q]->dirty = true;
  return id;
}

// Fewer than 3 boundary samples, or all of them on one line (relative to their spread).
bool degenerateBoundary(const std::vector<BoundaryPoint>& bp) {
  if (bp.size() < 3) return true;
  double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
  for (const auto& b : bp) minx = std::min(minx, b.x), maxx = std::max(maxx, b.x), miny = std::min(miny, b.y), maxy = std::max(maxy, b.y);
  const double span = std::max(maxx - minx, maxy - miny);
  if (!(span > 0)) return true;
  // the point farthest from the line through the first point and the point farthest from it
  size_t far = 0;
  double d2 = 0;
  for (size_t i = 1; i < bp.size(); ++i) {
    double dd = sq(bp[i].x - bp[0].x) + sq(bp[i].y - bp[0].y);
    if (dd > d2) d2 = dd, far = i;
  }
  double ex = bp[far].x - bp[0].x, ey = bp[far].y - bp[0].y, l = std::sqrt(d2), off = 0;
  for (const auto& b : bp) off = std::max(off, std::abs((b.x - bp[0].x) * ey - (b.y - bp[0].y) * ex) / l);
  return off < 1e-6 * span;
}

// The closed polygon through a patch's boundary points, in order.
planar::Pslg boundaryPslg(const std::vector<BoundaryPoint>& bp) {
  planar::Pslg pslg;
  for (const auto& b : bp) pslg.points.insert(pslg.points.end(), {b.x, b.y});
  for (uint32_t i = 0; i < bp.size(); ++i) pslg.segments.insert(pslg.segments.end(), {i, uint32_t((i + 1) % bp.size())});
  return pslg;
}

// The segments of a closed boundary polygon that cross another one (or fold back onto their
// neighbour), by exact orientation tests over all pairs: only used when refinement rejected the
// polygon, which is rare.
std::vector<uint32_t> crossingSegments(const planar::Pslg& pslg) {
  const uint32_t n = uint32_t(pslg.segments.size() / 2);
  const double* P = pslg.points.data();
  auto pt = [&](uint32_t s, int end) { return P + 2 * pslg.segments[2 * s + end]; };
  auto sgn = [](double x) { return (x > 0) - (x < 0); };
  std::vector<uint8_t> bad(n, 0);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j) {
      const double *a = pt(i, 0), *b = pt(i, 1), *c = pt(j, 0), *d = pt(j, 1);
      const bool adjacent = pslg.segments[2 * i + 1] == pslg.segments[2 * j] || pslg.segments[2 * j + 1] == pslg.segments[2 * i];
      if (adjacent) {
        // shared endpoint m, far ends x (of i) and y (of j): they fold back when collinear and
        // on the same side of m
        const bool iFirst = pslg.segments[2 * i + 1] == pslg.segments[2 * j];
        const double* m = iFirst ? b : a;
        const double* x = iFirst ? a : b;
        const double* y = iFirst ? d : c;
        if (planar::orient2d(x, m, y) == 0 && (x[0] - m[0]) * (y[0] - m[0]) + (x[1] - m[1]) * (y[1] - m[1]) > 0) bad[i] = bad[j] = 1;
        continue;
      }
      const int o1 = sgn(planar::orient2d(a, b, c)), o2 = sgn(planar::orient2d(a, b, d));
      const int o3 = sgn(planar::orient2d(c, d, a)), o4 = sgn(planar::orient2d(c, d, b));
      if (o1 * o2 > 0 || o3 * o4 > 0) continue;
      if (o1 == 0 && o2 == 0) {  // collinear: crossing only when the spans overlap
        const int k = std::abs(b[0] - a[0]) >= std::abs(b[1] - a[1]) ? 0 : 1;
        const double lo1 = std::min(a[k], b[k]), hi1 = std::max(a[k], b[k]), lo2 = std::min(c[k], d[k]), hi2 = std::max(c[k], d[k]);
        if (hi1 < lo2 || hi2 < lo1) continue;
      }
      bad[i] = bad[j] = 1;
    }
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < n; ++i)
    if (bad[i]) out.push_back(i);
  return out;
}

// Lift a planar point onto the input surface. The PSLG's boundary segments are chords of the
// flattened boundary (between curve samples), so a refinement vertex near a concave stretch of
// boundary can lie just outside the flattened patch: it is lifted from the nearest point of the
// flattened boundary polyline instead (on the input's boundary curve, within the chord's sagitta).
// hintFace: a face of the final layout near (x, y) to start the point location from (-1: none).
bool Pipeline::liftPoint(const PatchWork& w, double x, double y, PullbackPoint& q, int hintFace) const {
  const Pullback& pb = w.flat.pullback;
  if (pb.locate(x, y, hintFace, q, 1e-9)) return true;
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  double best = INFINITY, bx = x, by = y;
  for (const auto& h : loop) {
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    double ex = uv[2 * b] - uv[2 * a], ey = uv[2 * b + 1] - uv[2 * a + 1], l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? std::clamp(((x - uv[2 * a]) * ex + (y - uv[2 * a + 1]) * ey) / l2, 0.0, 1.0) : 0.0;
    double px = uv[2 * a] + t * ex, py = uv[2 * a + 1] + t * ey, d = dmath::hypot(px - x, py - y);
    if (d < best) best = d, bx = px, by = py;
  }
  return std::isfinite(best) && pb.locate(bx, by, q, 1e-6);
}

void Pipeline::meshPatch(uint32_t p, bool splitSegments) {
  PatchWork& w = *work_[p];
  w.builtAt = ++stamp_;
  w.dirty = false;
  w.needsMesh = false;
  w.optimized = false;
  std::vector<BoundaryPoint> bp = boundaryPoints(w);
  // A small patch bounded by short curves can have fewer than 3 boundary samples, or only
  // collinear ones (two curves between the same two corners): add a sample in the middle of the
  // longest boundary stretch (shared with the neighbour like any segment split) until it has a
  // proper polygon.
  for (int guard = 0; guard < 8 && degenerateBoundary(bp); ++guard) {
    size_t longest = 0;
    double best = -1;
    for (size_t i = 0; i < bp.size(); ++i) {
      // its length along the flattened boundary
      double len = 0;
      const auto& loop = w.pm.boundaryLoops[0];
      for (const Piece& pc : stretch(w, bp[i], bp[(i + 1) % bp.size()], bp.size())) {
        const auto& h = loop[pc.k];
        uint32_t va = w.pm.mesh.triangles[3 * h.face + h.corner], vb = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
        len += (pc.t1 - pc.t0) * dmath::hypot(w.flat.uv[2 * vb] - w.flat.uv[2 * va], w.flat.uv[2 * vb + 1] - w.flat.uv[2 * va + 1]);
      }
      if (len > best) best = len, longest = i;
    }
    addSplitSample(w, bp, uint32_t(longest), 0.5);
    w.builtAt = ++stamp_;
    w.dirty = false;
    bp = boundaryPoints(w);
  }
  if (degenerateBoundary(bp)) fail(Code::InternalError, Stage::Refine, "patch " + std::to_string(p) + ": its boundary samples do not make a polygon");
  planar::Pslg pslg = boundaryPslg(bp);
  pslg.points.insert(pslg.points.end(), w.requiredPoints.begin(), w.requiredPoints.end());
  planar::RefineOptions ro;
  // Diametral lenses: far fewer segment splits, so fewer samples a neighbour must take up and
  // fewer rounds. The planar bound has a margin over the 3D one for the small angle distortion
  // of the lift (the map is conformal only in the discrete sense; measured: ≤ ~1.5° on the
  // models in ../shared/data with the free boundary).
  ro.diametralLens = true;
  ro.splitSegments = splitSegments;
  ro.minAngleDeg = std::min(opt_.minAngleDeg + kPlanarAngleMargin, 34.0);
  // off-center factor for kOffcenterApexDeg: the off-center of factor f sits f / (2 tan(θ/2))
  // shortest-edge lengths from that edge, where it sees the edge under 2 atan(tan(θ/2) / f)
  // (refine.h); never above the planar default (bounds near 45° would otherwise get it)
  if (ro.minAngleDeg > 0)
    ro.offcenterFactor = std::min(0.95, dmath::tan(0.5 * ro.minAngleDeg * kPi / 180) / dmath::tan(0.5 * kOffcenterApexDeg * kPi / 180));
  // Boundary pieces shorter than this are not split: far below any size the output can mean,
  // and above the resolution at which two splits of one input edge are told apart (the sample
  // dedupe in addSplitSample); refinements that keep splitting each other's segments stop here.
  // A planar length l is l / s on the surface where the planar/3D scale is s: with the patch's
  // smallest scale the limit is at most kMinSegmentFactor · minLength on the surface anywhere in
  // the patch (less where the scale is larger), so it never stops a split the sizing asks for.
  ro.minSegmentLength = kMinSegmentFactor * sizing_.minLength * *std::min_element(w.scaleSub.begin(), w.scaleSub.end());
  // Longest-edge bound of the refinement vs the mean edge length it gives: calibrated so the
  // mean output edge length in flat regions is the target.
  const double kSizeFactor = 1.3;
  // The size at a planar point: h and the planar/3D scale interpolated in the face of the
  // flattened triangulation that contains it (it has the sub-mesh's vertices), found by a walk
  // from the face of the previous query (the refinement asks about nearby points in a row).
  const Pullback& pb = w.flat.pullback;
  int sizingFace = -1;
  const SpotField spots(w.spots);
  ro.sizing = [&](double x, double y) {
    int fv[3];
    double b[3];
    if (!pb.locateLayout(x, y, sizingFace, fv, b, 1e-6)) return double(INFINITY);
    double h = 0, s = 0;
    for (int c = 0; c < 3; ++c) {
      h += b[c] * w.hSub[uint32_t(fv[c])];
      s += b[c] * w.scaleSub[uint32_t(fv[c])];
    }
    return spots.size(x, y, kSizeFactor * h * s);
  };
  double area3 = 0;
  for (uint32_t f : w.pm.faceInput) area3 += g_.faceArea(f);
  ro.maxInsertions = size_t(std::min(4e7, 50.0 * area3 / (sizing_.minLength * sizing_.minLength) + 1e5));
  planar::RefineResult rr;
  for (int attempt = 0;; ++attempt) {
    try {
      rr = planar::refinePslg(pslg, ro);
      break;
    } catch (const Error& e) {
      if (e.code() != Code::InvalidPslg || attempt >= kCrossingRepairs) throw;
    }
    // The chords between boundary samples cross where the boundary doubles back within a sample
    // spacing: split the crossing chords (shared with the neighbours like any segment split)
    // and try again.
    const std::vector<uint32_t> crossing = crossingSegments(pslg);
    if (crossing.empty()) fail(Code::InternalError, Stage::Refine, "patch " + std::to_string(p) + ": invalid boundary, but no chords cross");
    for (uint32_t sg : crossing) addSplitSample(w, bp, sg, 0.5);
    w.builtAt = ++stamp_;
    w.dirty = false;
    bp = boundaryPoints(w);
    pslg = boundaryPslg(bp);
    pslg.points.insert(pslg.points.end(), w.requiredPoints.begin(), w.requiredPoints.end());
  }
  if (!rr.status.ok()) fail(rr.status.code, Stage::Refine, "patch " + std::to_string(p) + ": " + rr.status.message);
  dropUnusedPoints(rr.mesh, bp.size());
  spatialOrder(rr.mesh, bp.size());
  const auto& pmsh = rr.mesh;
  auto tl = std::chrono::steady_clock::now();
  const size_t nv = pmsh.vertexCount();
  w.localToGlobal.assign(nv, kNone);
  w.interiorPositions.assign(nv, F::Vec3{});
  w.layoutFaces.assign(nv, -1);
  w.liftFaces.assign(nv, kNone);
  w.optimizeCache = {};
  int lastFace = -1;
  for (size_t v = 0; v < nv; ++v) {
    if (v < bp.size()) {
      w.localToGlobal[v] = bp[v].sample;
      continue;
    }
    // every segment is a boundary chord (the required points are free), so a Steiner vertex on
    // a segment is a boundary split (segment i joins boundary points i and i + 1)
    if (const int32_t sg = pmsh.vertexSegment[v]; sg >= 0) {
      const uint32_t bs = uint32_t(sg);
      const double bt = pmsh.vertexParam[v];
      w.localToGlobal[v] = addSplitSample(w, bp, bs, bt);
      continue;
    }
    // the walk starts from the previous vertex's face (consecutive refinement vertices are
    // mostly near each other); a hinted locate finds the same point as the grid search
    PullbackPoint q;
    if (!liftPoint(w, pmsh.points[2 * v], pmsh.points[2 * v + 1], q, lastFace))
      fail(Code::NumericalFailure, Stage::Lift, "a refinement vertex lies outside the flattened patch");
    lastFace = q.layoutFace;
    w.interiorPositions[v] = {q.position[0], q.position[1], q.position[2]};
    w.layoutFaces[v] = q.layoutFace;
    w.liftFaces[v] = w.pm.faceInput[q.face];
  }
  w.triangles = pmsh.triangles;
  w.planarPoints = pmsh.points;
  liftSeconds_ += elapsed(tl);
}

// Optimize a patch's latest meshing in its plane, judged in 3D (remesh/optimize.h).
void Pipeline::optimizeMesh(uint32_t p, const std::vector<uint8_t>& active) {
  PatchWork& w = *work_[p];
  w.optimized = true;
  if (!opt_.optimize || opt_.optimizeIterations == 0) return;
  auto t0 = std::chrono::steady_clock::now();
  const size_t nv = w.planarPoints.size() / 2;
  std::vector<F::Vec3> pos(nv);
  std::vector<uint8_t> fixed(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    fixed[v] = w.localToGlobal[v] != kNone;
    pos[v] = fixed[v] ? cm_.samples[w.localToGlobal[v]].position : w.interiorPositions[v];
  }
  optimization::OptimizeOptions oo;
  oo.minAngleDeg = opt_.minAngleDeg;
  oo.maxIterations = opt_.optimizeIterations;
  oo.tolerance = opt_.optimizeTolerance;
  // per vertex: the layout face its latest lift landed in, where the next one starts looking
  auto lift = [&](uint32_t v, double x, double y, F::Vec3& out) {
    PullbackPoint q;
    if (!liftPoint(w, x, y, q, w.layoutFaces[v])) return false;
    w.layoutFaces[v] = q.layoutFace;
    w.liftFaces[v] = w.pm.faceInput[q.face];  // of the latest candidate: a hint, near the kept one
    out = {q.position[0], q.position[1], q.position[2]};
    return true;
  };
  // the patch's input vertices guard every optimization (optimize.h): no move or flip takes the
  // output farther from them than the chord tolerance, or farther than it was: unguarded, the
  // first one raised the Hausdorff distance for no gain in angles (docs/decisions/0011)
  optimization::SurfaceSamples guard;
  const double tolerance = chordTolerance();
  // a patch within tolerance/2 of a plane needs no guard: the input patch and every output
  // triangle over it (vertices on the input) lie in that slab and share the boundary curves, so
  // no moving can take the output farther than the tolerance from the input there (a CAD model's
  // flat faces), and the guard's bucketing is saved
  if (w.slabHalfWidth < 0) w.slabHalfWidth = slabHalfWidth(w.pm);
  if (!(w.slabHalfWidth <= 0.5 * tolerance)) {
    guard.xy = w.flat.uv;
    guard.pos.resize(w.pm.vertexInput.size());
    for (size_t v = 0; v < guard.pos.size(); ++v) guard.pos[v] = g_.positions[w.pm.vertexInput[v]];
    guard.tolerance = tolerance;
  }
  // between two optimizations of one meshing only slides move vertices, and `active` has every
  // vertex of a slid sample's stars
  optimization::OptimizeStats st = optimization::optimizePatch(w.planarPoints, w.triangles, pos, fixed, lift, oo, active, guard, &w.optimizeCache);
  for (size_t v = 0; v < nv; ++v)
    if (!fixed[v]) w.interiorPositions[v] = pos[v];
  rep_.optimizeMoves += st.moves;
  rep_.optimizeFlips += st.flips;
  optimizeSeconds_ += elapsed(t0);
}


// Curve samples slide along their input edge (issue 9), in every patch that holds them at once
// (a curve sample is shared by the patches on both sides): its 3D position moves along the input
// edge and its planar position along that edge's image in each patch's layout. Candidates: toward
// the 3D midpoint of its two neighbours along the curve (full and half step) and six points
// spread over its free interval (no lift is needed on a curve, so the search is cheap); the best
// kept one wins. A slide is kept under optimizePatch's rule over the union of the sample's stars
// in all those patches: no planar triangle inverts, every 3D min angle stays >= the bound, and
// their sum grows (stars with a triangle under the bound do not slide). The sample stays strictly
// inside its input edge, so on the feature curve and on the surface, and never passes another
// sample of that edge; the input curve's vertices between its two neighbours never get farther
// from the chords. Two passes at most (the second over the samples next to one that slid).
// Returns, per patch, the vertices whose star changed (empty when none): where to optimize again.
std::vector<std::vector<uint8_t>> Pipeline::slideSamples() {
  std::vector<std::vector<uint8_t>> slid(work_.size());
  auto t0 = std::chrono::steady_clock::now();
  const size_t nS = cm_.samples.size();
  const double bound = opt_.minAngleDeg;
  struct Hold {
    uint32_t p, v;
  };
  // per patch: vertex -> triangles (CSR), cached 3D min angle per triangle, and per input edge
  // the boundary loop halfedges that lie on it
  struct Star {
    std::vector<uint32_t> start, tri;
    std::vector<double> minAngle;
    std::vector<std::pair<uint32_t, uint32_t>> loopOfEdge;  // (input edge, loop halfedge), sorted
  };
  std::vector<Star> stars(work_.size());
  std::vector<std::vector<Hold>> holds(nS);
  auto pos3 = [&](const PatchWork& w, uint32_t v) -> const F::Vec3& {
    return w.localToGlobal[v] != kNone ? cm_.samples[w.localToGlobal[v]].position : w.interiorPositions[v];
  };
  for (uint32_t p = 0; p < work_.size(); ++p) {
    const PatchWork& w = *work_[p];
    Star& st = stars[p];
    const size_t nv = w.localToGlobal.size(), nt = w.triangles.size() / 3;
    // the latest optimization's stars when it left them (the same triangles)
    if (work_[p]->optimizeCache.starStart.size() == nv + 1) {
      st.start.swap(work_[p]->optimizeCache.starStart);
      st.tri.swap(work_[p]->optimizeCache.starTri);
    } else {
      vertexStars(w.triangles, nv, st.start, st.tri);
    }
    // the patch's latest optimization left these very values (minAngleDeg3Approx of the same
    // positions: only optimizations and slides move vertices, and each keeps them current; a
    // slide stores the exact values of the stars it changed, within 1e-5 degrees of those)
    if (work_[p]->optimizeCache.minAngle.size() == nt) {
      st.minAngle.swap(work_[p]->optimizeCache.minAngle);
    } else {
      st.minAngle.resize(nt);
      for (size_t t = 0; t < nt; ++t)
        st.minAngle[t] = optimization::minAngleDeg3Approx(pos3(w, w.triangles[3 * t]), pos3(w, w.triangles[3 * t + 1]), pos3(w, w.triangles[3 * t + 2]));
    }
    const auto& loop = w.pm.boundaryLoops[0];
    for (uint32_t k = 0; k < loop.size(); ++k) st.loopOfEdge.push_back({g_.faceEdges[w.pm.faceInput[loop[k].face]][loop[k].corner], k});
    std::sort(st.loopOfEdge.begin(), st.loopOfEdge.end());
    for (uint32_t v = 0; v < nv; ++v)
      if (w.localToGlobal[v] != kNone) holds[w.localToGlobal[v]].push_back({p, v});
  }
  // planar position in patch w of the point at parameter t of input edge e, on loop halfedge k
  auto planarAt = [&](const PatchWork& w, uint32_t k, uint32_t e, double t, double out[2]) {
    const auto& h = w.pm.boundaryLoops[0][k];
    const uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    const double tt = g_.edgeVerts[e][0] == w.pm.vertexInput[a] ? t : 1.0 - t;
    const auto& uv = w.flat.uv;
    out[0] = uv[2 * a] + tt * (uv[2 * b] - uv[2 * a]);
    out[1] = uv[2 * a + 1] + tt * (uv[2 * b + 1] - uv[2 * a + 1]);
  };
  constexpr int kPasses = 2;  // hard cap
  std::vector<double> fresh;
  std::vector<std::array<double, 2>> newXY;
  std::vector<uint32_t> loopK, nb;
  // a sample is tried again in the next pass when a sample of its star slid
  std::vector<uint8_t> activeS(nS, 1), nextS(nS, 0);
  for (int pass = 0; pass < kPasses; ++pass) {
    size_t slides = 0;
    std::fill(nextS.begin(), nextS.end(), 0);
    for (uint32_t s = 0; s < nS; ++s) {
      F::CurveSample& smp = cm_.samples[s];
      if (!activeS[s] || smp.vertex != kNone || smp.edge == kNone || holds[s].empty()) continue;
      const uint32_t e = smp.edge;
      // the free interval on the edge: up to the nearest samples on it (or its ends)
      double lo = 0, hi = 1;
      for (uint32_t o : edgeSamples_[e]) {
        if (o == s) continue;
        const double to = cm_.samples[o].t;
        if (to < smp.t) lo = std::max(lo, to);
        else hi = std::min(hi, to);
      }
      // the sample's neighbours along its curve: the other ends of its boundary edges in the
      // first patch that holds it (an edge of one triangle only)
      const Hold h0 = holds[s][0];
      const PatchWork& w0 = *work_[h0.p];
      const Star& st0 = stars[h0.p];
      nb.clear();
      for (uint32_t i = st0.start[h0.v]; i < st0.start[h0.v + 1]; ++i) {
        const uint32_t* t = &w0.triangles[3 * size_t(st0.tri[i])];
        for (int c = 0; c < 3; ++c)
          if (t[c] == h0.v) {
            nb.push_back(t[(c + 1) % 3]);
            nb.push_back(t[(c + 2) % 3]);
          }
      }
      std::sort(nb.begin(), nb.end());
      F::Vec3 mid{0, 0, 0};
      uint32_t endSample[2] = {kNone, kNone};
      int ends = 0;
      for (size_t i = 0; i < nb.size(); ++i) {
        const bool single = (i == 0 || nb[i - 1] != nb[i]) && (i + 1 == nb.size() || nb[i + 1] != nb[i]);
        if (single && w0.localToGlobal[nb[i]] != kNone) {
          mid = mid + pos3(w0, nb[i]);
          if (ends < 2) endSample[ends] = w0.localToGlobal[nb[i]];
          ++ends;
        }
      }
      if (ends != 2) continue;
      mid = mid * 0.5;
      // the input curve between the two neighbours: its vertices must not end up farther from
      // the chords than they are now (the slide keeps the curve's chordal deviation)
      const uint32_t cv = seg_.edgeCurve[e];
      if (cv == kNone) continue;
      const auto& cids = cm_.curveSamples[cv];
      if (cids.front() == cids.back() && (endSample[0] == cids.front() || endSample[1] == cids.front())) continue;
      double kPrev = curveKey(cv, endSample[0]), kNext = curveKey(cv, endSample[1]);
      if (kPrev > kNext) std::swap(kPrev, kNext), std::swap(endSample[0], endSample[1]);
      const double kSelf = curveKey(cv, s);
      if (!(kPrev < kSelf && kSelf < kNext)) continue;
      const auto& cverts = seg_.curves[cv].vertices;
      auto segDist = [](const F::Vec3& p, const F::Vec3& a, const F::Vec3& b) {
        const F::Vec3 ab = b - a;
        const double l = F::dot(ab, ab);
        const double u = l > 0 ? std::clamp(F::dot(p - a, ab) / l, 0.0, 1.0) : 0.0;
        return F::norm(p - (a + ab * u));
      };
      auto deviation = [&](const F::Vec3& S, double kS) {
        double d = 0;
        for (size_t i = size_t(std::floor(kPrev)) + 1; i < cverts.size() && double(i) < kNext; ++i) {
          const F::Vec3& X = g_.positions[cverts[i]];
          d = std::max(d, double(i) < kS ? segDist(X, cm_.samples[endSample[0]].position, S) : segDist(X, S, cm_.samples[endSample[1]].position));
        }
        return d;
      };
      const double devOld = deviation(smp.position, kSelf);
      const F::Vec3 A = g_.positions[g_.edgeVerts[e][0]], B = g_.positions[g_.edgeVerts[e][1]], AB = B - A;
      const double l2 = F::dot(AB, AB);
      if (!(l2 > 0)) continue;
      // stay clear of the neighbouring samples on the edge by a tenth of the free interval
      const double margin = 0.1 * (hi - lo);
      const double target = std::clamp(F::dot(mid - A, AB) / l2, lo + margin, hi - margin);
      // the loop halfedge of each hold: the one on edge e whose point at t is where the sample is
      loopK.assign(holds[s].size(), kNone);
      for (size_t i = 0; i < holds[s].size(); ++i) {
        const PatchWork& w = *work_[holds[s][i].p];
        const auto& loe = stars[holds[s][i].p].loopOfEdge;
        const auto range = std::equal_range(loe.begin(), loe.end(), std::pair<uint32_t, uint32_t>{e, 0},
                                            [](const auto& a, const auto& b) { return a.first < b.first; });
        double best = INFINITY;
        for (auto it = range.first; it != range.second; ++it) {
          const uint32_t k = it->second;
          double q[2];
          planarAt(w, k, e, smp.t, q);
          const double d = dmath::hypot(q[0] - w.planarPoints[2 * holds[s][i].v], q[1] - w.planarPoints[2 * holds[s][i].v + 1]);
          if (d < best) best = d, loopK[i] = k;
        }
      }
      if (std::find(loopK.begin(), loopK.end(), kNone) != loopK.end()) continue;
      // a seam (a cut with the same patch on both sides) whose two stars share a triangle: the
      // angles of that triangle would be judged with one copy moved at a time
      bool shared = false;
      for (size_t i = 0; i < holds[s].size() && !shared; ++i)
        for (size_t j = i + 1; j < holds[s].size() && !shared; ++j) {
          const Hold &a = holds[s][i], &b = holds[s][j];
          if (a.p != b.p) continue;
          for (uint32_t x = stars[a.p].start[a.v]; x < stars[a.p].start[a.v + 1] && !shared; ++x)
            for (uint32_t y = stars[b.p].start[b.v]; y < stars[b.p].start[b.v + 1] && !shared; ++y)
              shared = stars[a.p].tri[x] == stars[b.p].tri[y];
        }
      if (shared) continue;
      double oldMin = 180, oldSum = 0;
      for (const Hold& hd : holds[s])
        for (uint32_t i = stars[hd.p].start[hd.v]; i < stars[hd.p].start[hd.v + 1]; ++i) {
          const double a = stars[hd.p].minAngle[stars[hd.p].tri[i]];
          oldMin = std::min(oldMin, a);
          oldSum += a;
        }
      // a star with a triangle under the bound does not slide: which of those triangles an exempt
      // corner owns depends on where the curve samples are (see exemptCornerOf)
      if (oldMin < bound) continue;
      const double floor = bound;
      // evaluate a candidate parameter: false when it is refused (the rule of the header comment)
      // (exact: with the exact angles; else with minAngleDeg3Approx, within 1e-4 degrees, to rank)
      auto evaluate = [&](double t, bool exact, double& newMin, double& newSum, std::vector<double>& angles, std::vector<std::array<double, 2>>& xy) {
        if (!(t > lo && t < hi) || t == smp.t) return false;
        const F::Vec3 P = A * (1.0 - t) + B * t;
        if (deviation(P, kSelf) > devOld) return false;  // the side of each curve vertex does not change within the edge
        newMin = 180, newSum = 0;
        angles.clear();
        xy.assign(holds[s].size(), {0, 0});
        for (size_t i = 0; i < holds[s].size(); ++i) {
          const Hold& hd = holds[s][i];
          const PatchWork& w = *work_[hd.p];
          planarAt(w, loopK[i], e, t, xy[i].data());
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j) {
            const uint32_t* tv = &w.triangles[3 * size_t(stars[hd.p].tri[j])];
            const double* c[3];
            F::Vec3 q[3];
            for (int k = 0; k < 3; ++k) {
              c[k] = tv[k] == hd.v ? xy[i].data() : &w.planarPoints[2 * size_t(tv[k])];
              q[k] = tv[k] == hd.v ? P : pos3(w, tv[k]);
            }
            const double e2 = std::max({(c[1][0] - c[0][0]) * (c[1][0] - c[0][0]) + (c[1][1] - c[0][1]) * (c[1][1] - c[0][1]),
                                        (c[2][0] - c[1][0]) * (c[2][0] - c[1][0]) + (c[2][1] - c[1][1]) * (c[2][1] - c[1][1]),
                                        (c[0][0] - c[2][0]) * (c[0][0] - c[2][0]) + (c[0][1] - c[2][1]) * (c[0][1] - c[2][1])});
            if (!(planar::orient2d(c[0], c[1], c[2]) > 1e-6 * e2)) return false;
            const double a = exact ? optimization::minAngleDeg3(q[0], q[1], q[2]) : optimization::minAngleDeg3Approx(q[0], q[1], q[2]);
            if (!(a >= 0)) return false;  // NaN: a degenerate corner
            angles.push_back(a);
            newMin = std::min(newMin, a);
            newSum += a;
          }
        }
        return newMin >= floor && newSum > oldSum + 1e-9 * double(angles.size());
      };
      // candidates: toward the midpoint (full and half step), and evenly over the free interval
      // (no lift is needed on a curve, so a search is cheap); the best kept one wins
      constexpr int kSpread = 6;
      double cand[2 + kSpread] = {target, 0.5 * (smp.t + target)};
      for (int i = 0; i < kSpread; ++i) cand[2 + i] = lo + margin + (hi - lo - 2 * margin) * (i + 0.5) / kSpread;
      double bestT = -1, bestSum = -INFINITY;
      for (const double t : cand) {
        double mn, sm;
        if (evaluate(t, false, mn, sm, fresh, newXY) && sm > bestSum) bestSum = sm, bestT = t;
      }
      double mn, sm;
      if (bestT < 0 || !evaluate(bestT, true, mn, sm, fresh, newXY)) continue;
      {
        const double t = bestT;
        const F::Vec3 P = A * (1.0 - t) + B * t;
        smp.t = t;
        smp.position = P;
        size_t f = 0;
        for (size_t i = 0; i < holds[s].size(); ++i) {
          const Hold& hd = holds[s][i];
          PatchWork& w = *work_[hd.p];
          w.planarPoints[2 * size_t(hd.v)] = newXY[i][0];
          w.planarPoints[2 * size_t(hd.v) + 1] = newXY[i][1];
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j) stars[hd.p].minAngle[stars[hd.p].tri[j]] = fresh[f++];
          // the star's vertices may move again now
          if (slid[hd.p].empty()) slid[hd.p].assign(w.localToGlobal.size(), 0);
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j)
            for (int c = 0; c < 3; ++c) {
              const uint32_t u = w.triangles[3 * size_t(stars[hd.p].tri[j]) + c];
              slid[hd.p][u] = 1;
              if (w.localToGlobal[u] != kNone) nextS[w.localToGlobal[u]] = 1;
            }
        }
        ++slides;
      }
    }
    rep_.optimizeMoves += slides;
    if (slides == 0) break;
    activeS.swap(nextS);
  }
  // the min angles, kept exact through the slides, go back for the next optimization
  // so do the stars
  for (uint32_t p = 0; p < work_.size(); ++p) {
    work_[p]->optimizeCache.minAngle.swap(stars[p].minAngle);
    work_[p]->optimizeCache.starStart.swap(stars[p].start);
    work_[p]->optimizeCache.starTri.swap(stars[p].tri);
  }
  optimizeSeconds_ += elapsed(t0);
  return slid;
}

// vertexFace: per output vertex, a face of the validated input it lies on or near (its lift's,
// or one beside its curve sample's input edge or vertex), kNone when unknown: a hint for the
// report's distance check.
MeshBuffers Pipeline::stitch(std::vector<uint32_t>& trianglePatch, std::vector<uint32_t>& vertexFace) const {
  MeshBuffers out;
  size_t nv = cm_.samples.size(), nt = 0;
  for (const auto& w : work_) {
    for (uint32_t g : w->localToGlobal) nv += g == kNone;
    nt += w->triangles.size() / 3;
  }
  out.positions.reserve(3 * nv);
  out.triangles.reserve(3 * nt);
  trianglePatch.clear();
  trianglePatch.reserve(nt);
  vertexFace.assign(nv, kNone);
  auto inputFace = [&](uint32_t gf) { return gf < pre_.faceOrigin.size() ? pre_.faceOrigin[gf] : kNone; };
  for (size_t i = 0; i < cm_.samples.size(); ++i) {
    const F::CurveSample& s = cm_.samples[i];
    out.positions.insert(out.positions.end(), {s.position.x, s.position.y, s.position.z});
    uint32_t e = s.edge;
    if (e == kNone && s.vertex != kNone && s.vertex < g_.vertexCount && g_.vertexEdgeStart[s.vertex] < g_.vertexEdgeStart[s.vertex + 1])
      e = g_.vertexEdgeIds[g_.vertexEdgeStart[s.vertex]];
    if (e != kNone && e < g_.edgeCount()) vertexFace[i] = inputFace(g_.edgeFaces[e][0] != kNone ? g_.edgeFaces[e][0] : g_.edgeFaces[e][1]);
  }
  for (uint32_t p = 0; p < work_.size(); ++p) {
    const PatchWork& w = *work_[p];
    std::vector<uint32_t> id(w.localToGlobal.size());
    for (size_t v = 0; v < id.size(); ++v) {
      if (w.localToGlobal[v] != kNone) id[v] = w.localToGlobal[v];
      else {
        id[v] = uint32_t(out.positions.size() / 3);
        const auto& q = w.interiorPositions[v];
        out.positions.insert(out.positions.end(), {q.x, q.y, q.z});
        if (w.liftFaces[v] != kNone) vertexFace[id[v]] = inputFace(w.liftFaces[v]);
      }
    }
    for (size_t t = 0; t < w.triangles.size(); t += 3) {
      out.triangles.insert(out.triangles.end(), {id[w.triangles[t]], id[w.triangles[t + 1]], id[w.triangles[t + 2]]});
      trianglePatch.push_back(p);
    }
  }
  return out;
}

// Every patch's planar data as stitched into `out` (same vertex numbering as stitch()).
std::vector<RemeshPatch> Pipeline::patchSnapshot(const MeshBuffers& out) const {
  std::vector<RemeshPatch> res(work_.size());
  uint32_t next = uint32_t(cm_.samples.size());
  for (size_t p = 0; p < work_.size(); ++p) {
    const PatchWork& w = *work_[p];
    RemeshPatch& r = res[p];
    r.layoutUv = w.flat.uv;
    r.layoutTriangles = w.pm.mesh.triangles;
    r.layoutInputFace = w.pm.faceInput;
    r.layoutFactor = w.flat.u;
    r.uv = w.planarPoints;
    r.triangles = w.triangles;
    r.outputVertex.resize(w.localToGlobal.size());
    for (size_t v = 0; v < w.localToGlobal.size(); ++v)
      r.outputVertex[v] = w.localToGlobal[v] != kNone ? w.localToGlobal[v] : next++;
  }
  if (next != out.vertexCount()) fail(Code::InternalError, Stage::Stitch, "patch snapshot does not match the stitched mesh");
  return res;
}

//! A triangle with a corner below this (degrees) has collapsed: never a wanted output.
constexpr double kCollapsedDeg = 1e-3;


// Smallest corner angle of triangle t in degrees (quality::minMaxAngle's, the report's measure);
// 0 for a degenerate triangle.
double triangleMinAngle(const MeshBuffers& m, size_t t) {
  double mn, mx;
  return quality::minMaxAngle(m, t, mn, mx) ? mn * 180.0 / kPi : 0.0;
}

//! Whether triangleMinAngle(m, t) < boundDeg, mostly without its atan2s: the corner cosines
//! u·v / (|u||v|), within a few ulp of the exact ones, decide when they are more than 1e-9 from
//! cosBound = cos(boundDeg) (|Δcos| ≤ |Δangle|, and the atan2 angles are within a few 1e-16 rad
//! of the exact ones); a triangle near the bound, or with sides near under- or overflow, is
//! measured.
bool minAngleBelow(const MeshBuffers& m, size_t t, double boundDeg, double cosBound) {
  F::Vec3 p[3];
  for (int c = 0; c < 3; ++c) {
    uint32_t v = m.triangles[3 * t + c];
    p[c] = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
  }
  constexpr double kApart = 1e-9;
  bool above = true;
  for (int c = 0; c < 3; ++c) {
    const F::Vec3 u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
    const double uu = F::dot(u, u), vv = F::dot(v, v);
    if (!(uu >= 1e-200 && uu <= 1e200 && vv >= 1e-200 && vv <= 1e200)) return triangleMinAngle(m, t) < boundDeg;
    const double cosA = F::dot(u, v) / (std::sqrt(uu) * std::sqrt(vv));
    if (cosA > cosBound + kApart) return true;
    above = above && cosA < cosBound - kApart;
  }
  return above ? false : triangleMinAngle(m, t) < boundDeg;
}

//! How the output's topology differs from the input's ("Euler characteristic 3 vs 2, 1
//! non-manifold edge"), or "" when it has the input's components, boundary loops and Euler
//! characteristic and no non-manifold edge or vertex.
std::string topologyDifference(const quality::TopologySummary& out, const quality::TopologySummary& in) {
  std::string s;
  const auto add = [&](const std::string& what) { s += (s.empty() ? "" : ", ") + what; };
  const auto count = [](size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  if (out.components != in.components) add(std::to_string(out.components) + " components vs " + std::to_string(in.components));
  if (out.boundaryLoops != in.boundaryLoops)
    add(std::to_string(out.boundaryLoops) + " boundary loops vs " + std::to_string(in.boundaryLoops));
  if (out.euler != in.euler) add("Euler characteristic " + std::to_string(out.euler) + " vs " + std::to_string(in.euler));
  if (out.genus >= 0 && in.genus >= 0 && out.genus != in.genus)
    add("genus " + std::to_string(out.genus) + " vs " + std::to_string(in.genus));
  if (out.nonManifoldEdges > 0) add(count(out.nonManifoldEdges, "non-manifold edge", "non-manifold edges"));
  if (out.nonManifoldVertices > 0) add(count(out.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices"));
  return s;
}

//! RemeshOptions::forceTopologyDefect: a flipped copy (b, a, c') of triangle 0 (a, b, c), c' a new
//! vertex at c, so edge ab has three triangles. The per-vertex and per-triangle arrays grow with it.
void addNonManifoldEdge(MeshBuffers& m, std::vector<uint32_t>& vertexFace, std::vector<uint8_t>& exemptVertex,
                        std::vector<uint32_t>& triPatch) {
  if (m.triangles.empty()) return;
  const uint32_t a = m.triangles[0], b = m.triangles[1], c = m.triangles[2], copy = uint32_t(m.vertexCount());
  for (int k = 0; k < 3; ++k) m.positions.push_back(m.positions[3 * size_t(c) + k]);
  if (!m.uvs.empty()) m.uvs.insert(m.uvs.end(), {m.uvs[2 * size_t(c)], m.uvs[2 * size_t(c) + 1]});
  m.triangles.insert(m.triangles.end(), {b, a, copy});
  vertexFace.push_back(vertexFace[c]);
  exemptVertex.push_back(0);
  triPatch.push_back(triPatch[0]);
}

RemeshResult Pipeline::run(const MeshBuffers& input) {
  RemeshResult res;
  auto t0 = std::chrono::steady_clock::now(), tStart = t0;
  if (!(opt_.minAngleDeg >= 0 && opt_.minAngleDeg <= 34))
    fail(Code::InvalidArgument, Stage::Api, "minAngle must be in [0, 34] degrees");
  if (!(opt_.maxScaleRatio > 1)) fail(Code::InvalidArgument, Stage::Api, "maxScaleRatio must be > 1");
  if (opt_.optimizeIterations < 0 || opt_.optimizeIterations > 1000)
    fail(Code::InvalidArgument, Stage::Api, "optimizeIterations must be in [0, 1000]");
  if (!(opt_.optimizeTolerance >= 0)) fail(Code::InvalidArgument, Stage::Api, "optimizeTolerance must be >= 0");
  checkCancel(Stage::Validate, 0);
  ValidatedMesh vm = validate(input);
  const MeshBuffers& in = vm.buffers;
  rep_.inputTriangles = in.triangleCount();
  rep_.inputVertices = in.vertexCount();
  for (const auto& wn : vm.report.warnings) rep_.warnings.push_back(wn.message);
  rep_.seconds.validate = elapsed(t0);

  checkCancel(Stage::Segment, 0);
  F::FeatureOptions fo;
  fo.featureAngleDeg = opt_.featureAngleDeg;
  fo.cornerTurnDeg = opt_.cornerTurnDeg;
  std::vector<std::array<uint32_t, 2>> userFeatures;
  for (const auto& e : opt_.featureEdges) {
    if (e[0] >= vm.inputToVertex.size() || e[1] >= vm.inputToVertex.size())
      fail(Code::InvalidArgument, Stage::Segment, "a feature edge refers to a vertex out of range");
    userFeatures.push_back({vm.inputToVertex[e[0]], vm.inputToVertex[e[1]]});
  }
  double target = 0, area = 0;
  {  // the target edge length (cut junctions are judged at about it)
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < in.vertexCount(); ++v)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], in.positions[3 * v + k]), hi[k] = std::max(hi[k], in.positions[3 * v + k]);
    target = opt_.targetEdgeLength > 0 ? opt_.targetEdgeLength : opt_.targetEdgeLengthRel * dmath::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    for (size_t f = 0; f < in.triangleCount(); ++f) {
      const uint32_t* t = &in.triangles[3 * f];
      F::Vec3 a{in.positions[3 * t[0]], in.positions[3 * t[0] + 1], in.positions[3 * t[0] + 2]};
      F::Vec3 b{in.positions[3 * t[1]], in.positions[3 * t[1] + 1], in.positions[3 * t[1] + 2]};
      F::Vec3 c{in.positions[3 * t[2]], in.positions[3 * t[2] + 1], in.positions[3 * t[2] + 2]};
      area += 0.5 * F::norm(F::cross(b - a, c - a));
    }
  }
  // over the limits already with the target alone: TooLarge before any heavy work
  if (target > 0) checkOutputEstimate(estimateFromTarget(area, target, in.triangleCount()), opt_);
  fo.junctionScale = target;
  fo.minFeatureLength = opt_.minFeatureLength >= 0 ? opt_.minFeatureLength : kMinFeatureFactor * target;
  // strips narrower than half the smallest edge the sizing allows (its minLength) are merged
  // into a neighbour (features/segmentation.h)
  fo.minPatchWidth = opt_.minPatchWidth >= 0 ? opt_.minPatchWidth : 0.5 * (opt_.minEdgeLength > 0 ? opt_.minEdgeLength : 0.1 * target);
  // the input's surface curvature per vertex of the preconditioned mesh (empty: not preconditioned)
  std::vector<double> surfaceKappa;
  {  // input edges no longer than twice the target, flat pairs Delaunay (mesh/precondition.h),
     // in the patches that need cuts (only there do curves follow input edges that are not
     // features): a first segmentation of the input finds them
    PreconditionOptions po;
    g_ = F::buildEdgeGraph(in);
    graphMesh_ = &in;
    F::FeatureOptions f0 = fo;
    f0.featureEdges = userFeatures;
    seg_ = F::segment(g_, f0, progress_);
    std::vector<uint8_t> cutPatch(seg_.patches.size(), 0);
    for (uint32_t e = 0; e < g_.edgeCount(); ++e)
      if (seg_.edgeKind[e] == F::EdgeKind::Cut)
        for (uint32_t f : g_.edgeFaces[e])
          if (f != F::kNone) cutPatch[seg_.facePatch[f]] = 1;
    po.faceMask.resize(in.triangleCount());
    for (uint32_t f = 0; f < in.triangleCount(); ++f) po.faceMask[f] = cutPatch[seg_.facePatch[f]];
    po.maxNewVertices = std::max<size_t>(200000, 2 * in.vertexCount());
    // a tiny target on a big surface must not split without end: no more new vertices than
    // the budget (the output limits are checked once the sizing is known)
    po.maxEdgeLength = target > 0 ? std::max(kPreconditionEdgeFactor * target, std::sqrt(area / (0.4 * double(po.maxNewVertices)))) : 0.0;
    // the creases found on the input, kept as they are on the preconditioned mesh (the crease
    // tests look at neighbourhoods, which the splits change)
    std::vector<std::array<uint32_t, 2>> creases = userFeatures;
    for (uint32_t e = 0; e < g_.edgeCount(); ++e)
      if (seg_.edgeKind[e] == F::EdgeKind::Feature) creases.push_back(g_.edgeVerts[e]);
    pre_ = precondition(in, creases, po);
    // no patch needs cuts, so nothing was changed: the segmentation of the input stands
    if (pre_.splits > 0 || pre_.flips > 0) {
      // the surface's curvature from the input as given (features/sizing.h), carried to the
      // split points (each the larger of its edge's two ends): the precondition's splits
      // depend on the target, and short split edges would change the estimate
      surfaceKappa = F::surfaceCurvature(g_);
      surfaceKappa.resize(pre_.mesh.vertexCount(), 0.0);
      for (size_t v = in.vertexCount(); v < surfaceKappa.size(); ++v)
        surfaceKappa[v] = std::max(surfaceKappa[pre_.parents[v][0]], surfaceKappa[pre_.parents[v][1]]);
      fo.featureEdges = pre_.protectedEdges;
      fo.detectCreases = false;
      g_ = F::buildEdgeGraph(pre_.mesh);
      graphMesh_ = &pre_.mesh;
      const uint32_t dropped = seg_.droppedFeatureEdges;
      seg_ = F::segment(g_, fo, progress_);
      seg_.droppedFeatureEdges = dropped;
    }
  }
  F::SizingOptions so;
  so.targetEdgeLength = opt_.targetEdgeLength;
  so.targetEdgeLengthRel = opt_.targetEdgeLengthRel;
  so.chordTolerance = opt_.chordTolerance;
  so.chordToleranceRel = opt_.chordToleranceRel;
  so.gradation = opt_.gradation;
  so.minEdgeLength = opt_.minEdgeLength;
  so.maxEdgeLength = opt_.maxEdgeLength;
  so.surfaceKappa = std::move(surfaceKappa);
  if (pre_.splits > 0) so.firstSplitVertex = uint32_t(in.vertexCount());
  if (!opt_.vertexSizing.empty()) {
    if (opt_.vertexSizing.size() != input.vertexCount())
      fail(Code::InvalidArgument, Stage::CurveMesh, "vertexSizing needs one value per input vertex");
    so.vertexSizing.resize(g_.vertexCount);
    for (size_t v = 0; v < so.vertexSizing.size(); ++v)
      so.vertexSizing[v] = v < in.vertexCount() ? opt_.vertexSizing[vm.vertexToInput[v]]
                                                : 0.5 * (so.vertexSizing[pre_.parents[v][0]] + so.vertexSizing[pre_.parents[v][1]]);
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
  std::vector<uint32_t> vertexFace, bestVertexFace;  // stitch(): an input face per output vertex (a hint)
  bool outIsBest = false;  // the best round is the current one: kept in out (moved, not copied)
  size_t bestBad = SIZE_MAX, bestCollapsed = SIZE_MAX, bestDoubled = SIZE_MAX;  // bestDoubled: stitch defects
  int staleRounds = 0;  // certificate rounds in a row that did not beat the best
  std::vector<std::vector<uint32_t>> bestCurveSamples;
  std::vector<RemeshPatch> bestPatches;
  const double cosBound = dmath::cos(opt_.minAngleDeg * kPi / 180.0), cosCollapsed = dmath::cos(kCollapsedDeg * kPi / 180.0);
  for (int cert = 0;; ++cert) {
    // Refine every patch that needs it; a refinement that splits a boundary segment adds a
    // curve sample there, which the patches on the other side of that curve must include: they
    // are refined again from scratch with it, until no patch splits a segment (samples only get
    // added, and each refinement is Ruppert's on its own, so this settles in a few rounds).
    int round = 0;
    for (;; ++round) {
      std::vector<uint32_t> todo;
      for (uint32_t p = 0; p < work_.size(); ++p)
        if (work_[p]->needsMesh || (work_[p]->dirty && round < kConformingRounds)) todo.push_back(p);
      if (todo.empty()) break;
      for (size_t i = 0; i < todo.size(); ++i) {
        meshPatch(todo[i], !work_[todo[i]]->keepBoundary);
        checkCancel(Stage::Refine, double(i + 1) / double(todo.size()));
      }
    }
    // past the round cap (refinements near small angles between curves can keep splitting
    // each other's segments): refine the patches still missing samples once more, without
    // splitting their boundary, so every patch has exactly the curve samples and they stitch
    for (uint32_t p = 0; p < work_.size(); ++p)
      if (work_[p]->dirty) {
        meshPatch(p, false);
        rep_.warnings.push_back("patch " + std::to_string(p) + ": refined without boundary splits after " +
                                std::to_string(kConformingRounds) + " conforming rounds");
      }
    for (uint32_t p = 0; p < work_.size(); ++p)
      if (!work_[p]->optimized) {
        optimizeMesh(p);
        checkCancel(Stage::Refine, 1.0);
      }
    // curve samples slide along their curves, then the interior around each slid sample gets
    // another optimization (local: the vertices of its stars first), guarded so that it does not
    // take the output farther from the input
    if (opt_.optimize && opt_.optimizeIterations > 0) {
      const std::vector<std::vector<uint8_t>> slid = slideSamples();
      for (uint32_t p = 0; p < work_.size(); ++p)
        if (!slid[p].empty()) {
          optimizeMesh(p, slid[p]);
          checkCancel(Stage::Refine, 1.0);
        }
    }
    rep_.conformingRounds = std::max(rep_.conformingRounds, round);
    rep_.seconds.refine += elapsed(t0);
    if (outIsBest) {
      bestOut = std::move(out);
      bestTriPatch = std::move(triPatch);
      bestVertexFace = std::move(vertexFace);
      outIsBest = false;
    }
    out = stitch(triPatch, vertexFace);
    // exempt corners: input vertices where the input's own feature or boundary curves make a
    // wedge below the bound. Cuts are ours (not features): a small angle where a cut meets a
    // curve is not exempt.
    if (exemptVertex.empty()) {
      exemptVertex.assign(out.vertexCount(), 0);
      rep_.exemptCorners.clear();
      const std::vector<double> wedge = F::featureWedgeAngles(g_, seg_);
      for (uint32_t iv = 0; iv < g_.vertexCount; ++iv) {
        if (iv >= in.vertexCount() || !(wedge[iv] * 180.0 / kPi < opt_.minAngleDeg)) continue;
        uint32_t s = iv < cm_.cornerSample.size() ? cm_.cornerSample[iv] : kNone;
        if (s == kNone || s >= exemptVertex.size() || exemptVertex[s]) continue;
        exemptVertex[s] = 1;
        exemptWedgeDeg_[s] = wedge[iv] * 180.0 / kPi;
        rep_.exemptCorners.push_back({vm.vertexToInput[iv], s, wedge[iv] * 180.0 / kPi, {}});
      }
    }
    exemptVertex.resize(out.vertexCount(), 0);
    indexExemptWedges(exemptVertex);
    // bad: below the bound outside exempt corners; collapsed: a corner below kCollapsedDeg (points
    // closer than the lift resolves, e.g. refinement cascading into a small exempt wedge). A round
    // never wins by trading bad triangles for collapsed ones.
    size_t bad = 0, collapsed = 0;
    for (size_t t = 0; t < out.triangleCount(); ++t) {
      if (minAngleBelow(out, t, kCollapsedDeg, cosCollapsed)) ++collapsed;
      if (minAngleBelow(out, t, opt_.minAngleDeg, cosBound) && exemptCornerOf(out, t, exemptVertex) == kNone) ++bad;
    }
    // the same three samples meshed as a triangle by two patches (a corner wedge between two
    // curves that both patches border, closed by one triangle on each side): the stitched
    // surface is not manifold there. Worse than any angle: a round with fewer always wins.
    const std::vector<size_t> doubled = doubledTriangles(out, triPatch);
    const std::vector<std::array<size_t, 2>> chords = sharedChords(out, triPatch);
    const size_t defects = doubled.size() + chords.size();
    if (defects < bestDoubled ||
        (defects == bestDoubled && (collapsed < bestCollapsed || (collapsed == bestCollapsed && bad < bestBad)))) {
      bestDoubled = defects;
      bestBad = bad;
      bestCollapsed = collapsed;
      outIsBest = true;
      bestCurveSamples = cm_.curveSamples;
      if (opt_.returnPatches) bestPatches = patchSnapshot(out);
      staleRounds = 0;
    } else if (++staleRounds >= 2 && bestDoubled == 0) {
      // Two rounds in a row no better than the best: what is left does not yield to size (a
      // corner whose planar and 3D angles differ, a cut meeting a curve at a small angle). A
      // single round that is not better is no reason to stop: the spots accumulate, and the
      // next round often gets there (docs/decisions/0008). While the
      // best round still has a stitch defect the rounds go on to their cap: a non-manifold
      // output is an error, worse than any angle.
      break;
    }
    // a stitch defect left at the cap gets kKeepBoundaryRounds more, its patches keeping their
    // boundary (PatchWork::keepBoundary): a non-manifold output is an error
    const int rounds = opt_.maxCertificateRounds + (bestDoubled > 0 ? kKeepBoundaryRounds : 0);
    if ((bad == 0 && defects == 0) || cert >= rounds) break;
    // 3D angle certificate: where a lifted triangle is below the bound, ask for smaller planar
    // triangles there (a graded spot at its planar centroid) and re-mesh the patch.
    std::vector<size_t> firstTri(work_.size(), 0);
    for (size_t i = triPatch.size(); i-- > 0;) firstTri[triPatch[i]] = i;
    // A doubled triangle closes a corner wedge of its patch alone: the patch must put a vertex
    // inside it, halfway from the wedge's corner (its largest angle) to the far side; a finer
    // size there would only split the two curves and close the wedge again one step closer.
    for (size_t t : doubled) {
      PatchWork& w = *work_[triPatch[t]];
      const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
      const double* q[3] = {&w.planarPoints[2 * lt[0]], &w.planarPoints[2 * lt[1]], &w.planarPoints[2 * lt[2]]};
      int corner = 0;
      double widest = -2;
      for (int c = 0; c < 3; ++c) {
        const double ux = q[(c + 1) % 3][0] - q[c][0], uy = q[(c + 1) % 3][1] - q[c][1];
        const double vx = q[(c + 2) % 3][0] - q[c][0], vy = q[(c + 2) % 3][1] - q[c][1];
        const double cosA = (ux * vx + uy * vy) / (dmath::hypot(ux, uy) * dmath::hypot(vx, vy));
        if (-cosA > widest) widest = -cosA, corner = c;
      }
      for (int k = 0; k < 2; ++k)
        w.requiredPoints.push_back(0.5 * q[corner][k] + 0.25 * (q[(corner + 1) % 3][k] + q[(corner + 2) % 3][k]));
      w.needsMesh = true;
      if (cert >= opt_.maxCertificateRounds) w.keepBoundary = true;
    }
    // A shared chord is split inside its patch: a vertex at its planar midpoint.
    for (const auto& [t, c] : chords) {
      PatchWork& w = *work_[triPatch[t]];
      const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
      const double* a = &w.planarPoints[2 * lt[c]];
      const double* b = &w.planarPoints[2 * lt[(c + 1) % 3]];
      w.requiredPoints.insert(w.requiredPoints.end(), {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
      w.needsMesh = true;
      if (cert >= opt_.maxCertificateRounds) w.keepBoundary = true;
    }
    for (size_t t = 0; t < out.triangleCount(); ++t) {
      if (!minAngleBelow(out, t, opt_.minAngleDeg, cosBound) || exemptCornerOf(out, t, exemptVertex) != kNone) continue;
      PatchWork& w = *work_[triPatch[t]];
      const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
      double cx = 0, cy = 0, longest = 0;
      for (int c = 0; c < 3; ++c) {
        cx += w.planarPoints[2 * lt[c]] / 3.0;
        cy += w.planarPoints[2 * lt[c] + 1] / 3.0;
        uint32_t a = lt[c], b = lt[(c + 1) % 3];
        longest = std::max(longest, dmath::hypot(w.planarPoints[2 * a] - w.planarPoints[2 * b],
                                               w.planarPoints[2 * a + 1] - w.planarPoints[2 * b + 1]));
      }
      w.spots.push_back({cx, cy, 0.5 * longest});
      w.needsMesh = true;
    }
    ++rep_.certificateRounds;
  }
  if (!outIsBest) {
    out = std::move(bestOut);
    triPatch = std::move(bestTriPatch);
    vertexFace = std::move(bestVertexFace);
  }
  // sized for the last round; the best one may have more vertices (only curve samples, the
  // first vertices of every round, can be exempt)
  exemptVertex.resize(out.vertexCount(), 0);
  cm_.curveSamples = std::move(bestCurveSamples);
  // what the certificate left below the bound: free vertices moved over the surface in 3D
  // (remesh/repair.h; counted in the stitch stage's time)
  if (bestBad > 0) {
    std::vector<uint8_t> pinned(out.vertexCount(), 0);
    for (size_t c = 0; c < seg_.curves.size(); ++c)
      if (seg_.curves[c].kind != F::EdgeKind::Cut)
        for (uint32_t s : cm_.curveSamples[c])
          if (s < pinned.size()) pinned[s] = 1;
    for (uint32_t s : cm_.cornerSample)
      if (s < pinned.size()) pinned[s] = 1;
    for (size_t v = 0; v < pinned.size(); ++v) pinned[v] |= exemptVertex[v];
    const auto isBad = [&](size_t t) {
      return minAngleBelow(out, t, opt_.minAngleDeg, cosBound) && exemptCornerOf(out, t, exemptVertex) == kNone;
    };
    // a repaired star may always be a quarter of the chord tolerance from the input
    const repair::RepairStats rs = repair::relaxBelowBound(out, vertexFace, triPatch, pinned, *graphMesh_, seg_.facePatch, isBad,
                                                           opt_.minAngleDeg, kRepairRounds, kRepairDeviationFloor * chordTolerance());
    rep_.repairMoves = rs.moves;
    if (rs.rounds >= kRepairRounds && rs.left > 0)
      rep_.warnings.push_back("repair stopped at its cap of " + std::to_string(kRepairRounds) + " passes with " +
                              std::to_string(rs.left) + " triangles below the bound");
  }
  if (opt_.forceTopologyDefect) addNonManifoldEdge(out, vertexFace, exemptVertex, triPatch);
  rep_.seconds.lift = liftSeconds_;
  rep_.seconds.refine -= liftSeconds_ + optimizeSeconds_;
  rep_.seconds.optimize = optimizeSeconds_;
  rep_.seconds.stitch = elapsed(t0);
  checkOutputCounts(out.vertexCount(), out.triangleCount(), opt_);  // remesh/limits.h

  // report. The patches' work is done: their memory goes back to the heap first, where the
  // report's buffers find it (fresh pages cost a fault each).
  rep_.patches = work_.size();
  for (const auto& w : work_) rep_.flowIterations.push_back(w->flat.report.iterations);
  work_.clear();
  std::vector<double> triMinRad;  // per triangle, NaN when degenerate
  auto as = quality::angleStats(out, &triMinRad);
  rep_.triangles = out.triangleCount();
  rep_.vertices = out.vertexCount();
  rep_.minAngle = as.minAngle;
  rep_.maxAngle = as.maxAngle;
  rep_.meanMinAngle = as.meanMinAngle;
  rep_.pctBelow20 = as.pctBelow20;
  rep_.pctBelow26 = as.pctBelow26;
  rep_.pctBelow30 = as.pctBelow30;
  if (as.triangles > 0) {
    size_t at40 = 0, at50 = 0;
    for (int b = 8; b < 13; ++b) at40 += as.minAngleHistogram[b];
    for (int b = 10; b < 13; ++b) at50 += as.minAngleHistogram[b];
    rep_.pctMinAtLeast40 = 100.0 * double(at40) / double(as.triangles);
    rep_.pctMinAtLeast50 = 100.0 * double(at50) / double(as.triangles);
  }
  rep_.minAngleOutsideExempt = 180;
  indexExemptWedges(exemptVertex);
  std::unordered_map<uint32_t, size_t> cornerIndex;
  for (size_t i = 0; i < rep_.exemptCorners.size(); ++i) cornerIndex[rep_.exemptCorners[i].outputVertex] = i;
  for (size_t t = 0; t < out.triangleCount(); ++t) {
    const uint32_t* tv = &out.triangles[3 * t];
    bool ex = false;
    for (int c = 0; c < 3; ++c)
      if (exemptVertex[tv[c]]) {
        ex = true;
        rep_.exemptCorners[cornerIndex.at(tv[c])].triangles.push_back(uint32_t(t));
      }
    if (!ex) {
      const uint32_t corner = exemptCornerOf(out, t, exemptVertex);
      if (corner != kNone) {
        ex = true;
        rep_.exemptCorners[cornerIndex.at(corner)].triangles.push_back(uint32_t(t));
      }
    }
    if (ex) continue;
    // the same value as triangleMinAngle (the same atan2s; degrees are monotone in radians)
    const double a = std::isnan(triMinRad[t]) ? triangleMinAngle(out, t) : triMinRad[t] * 180.0 / kPi;
    rep_.minAngleOutsideExempt = std::min(rep_.minAngleOutsideExempt, a);
    if (a < opt_.minAngleDeg) ++rep_.trianglesBelowBoundOutsideExempt;
  }
  const quality::EdgeTopology et = quality::edgeStatsAndTopology(out);
  rep_.meanEdgeLength = et.edges.meanLength;
  rep_.delaunayFraction = et.edges.delaunayFraction;
  const quality::TopologySummary ti = quality::topologySummary(in), &to = et.topology;
  // a broken mesh is never a success: a defect here is a bug of the stitch or the repair
  const std::string defect = topologyDifference(to, ti);
  rep_.topologyPreserved = defect.empty();
  Status topologyStatus;
  if (!defect.empty()) {
    topologyStatus = Status{Code::InternalError, Stage::Report, "output topology differs from the input: " + defect};
    if (!opt_.keepDefectiveOutput) fail(topologyStatus.code, topologyStatus.stage, topologyStatus.message);
  }
  // feature curves kept: every pair of consecutive samples is an output edge
  // (vertex -> neighbours in compressed rows: a hash set of every edge cost 5x more here)
  std::vector<uint32_t> nbrStart(out.vertexCount() + 1, 0), nbr(2 * out.triangles.size());
  for (uint32_t v : out.triangles) nbrStart[v + 1] += 2;
  for (size_t v = 0; v < out.vertexCount(); ++v) nbrStart[v + 1] += nbrStart[v];
  {
    std::vector<uint32_t> fill(nbrStart.begin(), nbrStart.end() - 1);
    for (size_t t = 0; t < out.triangles.size(); t += 3)
      for (int c = 0; c < 3; ++c) {
        uint32_t a = out.triangles[t + c], b = out.triangles[t + (c + 1) % 3];
        nbr[fill[a]++] = b;
        nbr[fill[b]++] = a;
      }
  }
  auto isEdge = [&](uint32_t a, uint32_t b) {
    return std::find(nbr.begin() + nbrStart[a], nbr.begin() + nbrStart[a + 1], b) != nbr.begin() + nbrStart[a + 1];
  };
  for (size_t c = 0; c < seg_.curves.size(); ++c) {
    if (seg_.curves[c].kind == F::EdgeKind::Cut) continue;
    ++rep_.featureCurves;
    bool kept = true;
    const auto& ids = cm_.curveSamples[c];
    for (size_t i = 0; i + 1 < ids.size() && kept; ++i) {
      kept = isEdge(ids[i], ids[i + 1]);
    }
    rep_.featureCurvesKept += kept;
  }
  rep_.sharpEdges = seg_.sharpEdgeCount;
  rep_.cutEdges = seg_.cutEdgeCount;
  rep_.droppedFeatureEdges = seg_.droppedFeatureEdges;
  rep_.curves = seg_.curves.size();
  rep_.curveSamples = cm_.samples.size();
  rep_.patchSplitsForScale = scaleSplits_;
  {
    quality::TriangleMeshDistance dist(in);
    double worst = 0;
    int64_t hint = -1;  // consecutive output vertices are near each other (curves, then patches)
    for (size_t v = 0; v < out.vertexCount(); ++v) {
      const quality::Vec3 p{out.positions[3 * v], out.positions[3 * v + 1], out.positions[3 * v + 2]};
      // the input face the vertex was lifted onto (or one beside its curve sample) bounds its
      // distance: at most the worst so far, the vertex cannot change the maximum
      if (vertexFace[v] < in.triangleCount()) {
        hint = vertexFace[v];
        if (dist.faceDistanceSquared(vertexFace[v], p) <= worst) continue;
      }
      auto hit = dist.closest(p, hint);
      hint = hit.primitive;
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
  res.status = topologyStatus;
  res.mesh = std::move(out);
  res.report = rep_;
  if (opt_.returnPatches) {
    res.patches = std::move(bestPatches);
    for (auto& rp : res.patches)
      for (uint32_t& f : rp.layoutInputFace) f = vm.faceToInput[pre_.faceOrigin[f]];
    res.patchOfTriangle = triPatch;
  }
  if (opt_.returnSurfacePoints || (opt_.carryAttributes && hasAttributes(input))) {  // remesh/carry_attributes.h
    std::vector<uint32_t> hint(vertexFace.size(), kNone);
    for (size_t v = 0; v < hint.size(); ++v)
      if (vertexFace[v] < in.triangleCount()) hint[v] = vm.faceToInput[vertexFace[v]];
    CornerPoints cp = locateCorners(input, res.mesh, hint);
    if (opt_.carryAttributes) interpolateAttributes(input, cp, res.mesh);
    res.cornerInputFace = std::move(cp.face);
    res.cornerBarycentric = std::move(cp.barycentric);
  }
  return res;
}

}  // namespace

RemeshResult remesh(const MeshBuffers& input, const RemeshOptions& options, ProgressFn progress) {
  RemeshResult r;
  try {
    // attribute seams are kept as feature curves (remesh/carry_attributes.h)
    std::vector<std::array<uint32_t, 2>> seams;
    if (options.carryAttributes) {
      checkAttributes(input, Stage::Api);
      seams = attributeSeams(input);
    }
    RemeshOptions withSeams;
    if (!seams.empty()) {
      withSeams = options;
      withSeams.featureEdges.insert(withSeams.featureEdges.end(), seams.begin(), seams.end());
    }
    Pipeline p(seams.empty() ? options : withSeams, progress);
    r = p.run(input);
    r.report.seamEdges = seams.size();
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
