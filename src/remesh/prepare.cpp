#include "remesh/prepare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/detmath.h"
#include "remesh/limits.h"
#include "remesh/max_error.h"

namespace conformesh::pipeline {
namespace {

// Default minFeatureLength in target edge lengths: a chain of sharp edges shorter than two
// output edges gets at most one sample inside, too few to carry a feature; on scans such chains
// are bumps of the noise, and each one needs cuts to join the rest (docs/decisions/0006).
constexpr double kMinFeatureFactor = 2.0;
// Input edges longer than this times the target edge length are split before segmentation, so
// cuts along input edges are not sawtooths of needle edges (mesh/precondition.h).
constexpr double kPreconditionEdgeFactor = 2.0;
// Error-driven remeshing: the largest edge, as a fraction of the diagonal, where the surface is
// flat (no chord error bounds it there; ten edges across the whole object).
constexpr double kErrorDrivenMaxSizeRel = 0.1;

}  // namespace

void checkOptions(const RemeshOptions& opt) {
  if (!(opt.minAngle >= 0 && opt.minAngle <= 35))
    fail(Code::InvalidArgument, Stage::Api, "minAngle must be in [0, 35] degrees");
  if (!(opt.maxScaleRatio > 1)) fail(Code::InvalidArgument, Stage::Api, "maxScaleRatio must be > 1");
  if (opt.optimizeIterations < 0 || opt.optimizeIterations > 1000)
    fail(Code::InvalidArgument, Stage::Api, "optimizeIterations must be in [0, 1000]");
  if (opt.threads < 0 || opt.threads > 1024) fail(Code::InvalidArgument, Stage::Api, "threads must be in [0, 1024]");
  if (!(opt.optimizeTolerance >= 0)) fail(Code::InvalidArgument, Stage::Api, "optimizeTolerance must be >= 0");
  if (!(opt.maxError > -INFINITY && opt.maxError < INFINITY)) fail(Code::InvalidArgument, Stage::Api, "maxError must be finite");
  if (opt.targetEdgeLength == 0)
    fail(Code::InvalidArgument, Stage::Api, "targetEdgeLength must be > 0, or < 0 for targetEdgeLengthRel times the diagonal");
  if (!(opt.maxErrorRel >= 0 && opt.maxErrorRel < INFINITY))
    fail(Code::InvalidArgument, Stage::Api, "maxErrorRel must be finite and >= 0");
}

Surface prepareSurface(ValidatedMesh vm, const MeshBuffers& input, const RemeshOptions& opt, const Progress& progress,
                       RemeshReport& rep, StageClock& clock) {
  Surface surf;
  surf.vm = std::move(vm);
  const MeshBuffers& in = surf.vm.buffers;
  F::FeatureOptions fo;
  fo.featureAngleDeg = opt.featureAngle;
  fo.cornerTurnDeg = opt.cornerTurn;
  fo.angleBoundDeg = opt.minAngle;
  fo.innerCreases = opt.innerCreases;
  std::vector<std::array<uint32_t, 2>> userFeatures;
  for (const auto& e : opt.featureEdges) {
    if (e[0] >= surf.vm.inputToVertex.size() || e[1] >= surf.vm.inputToVertex.size())
      fail(Code::InvalidArgument, Stage::Segment, "a feature edge refers to a vertex out of range");
    userFeatures.push_back({surf.vm.inputToVertex[e[0]], surf.vm.inputToVertex[e[1]]});
  }
  double target = 0, area = 0, diagonal = 0;
  {  // the target edge length (cut junctions are judged at about it)
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < in.vertexCount(); ++v)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], in.positions[3 * v + k]), hi[k] = std::max(hi[k], in.positions[3 * v + k]);
    diagonal = dmath::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    target = opt.targetEdgeLength > 0 ? opt.targetEdgeLength : opt.targetEdgeLengthRel * diagonal;
    for (size_t f = 0; f < in.triangleCount(); ++f) {
      const uint32_t* t = &in.triangles[3 * f];
      Vec3 a = vec3At(in.positions, t[0]), b = vec3At(in.positions, t[1]), c = vec3At(in.positions, t[2]);
      area += 0.5 * norm(cross(b - a, c - a));
    }
  }
  // over the limits already with the target alone: TooLarge before any heavy work
  if (target > 0) checkOutputEstimate(estimateFromTarget(area, target, in.triangleCount()), opt);
  fo.junctionScale = target;
  // error-driven too: the output spanning a dropped crease is held to the chord tolerance by the
  // sizing's bend bound (features/sizing.h), and noise kept as creases makes patches and corners
  fo.minFeatureLength = opt.minFeatureLength >= 0 ? opt.minFeatureLength : kMinFeatureFactor * target;
  // strips narrower than half the smallest edge the sizing allows (its minLength) are merged
  // into a neighbour (features/segmentation.h)
  fo.minPatchWidth = opt.minPatchWidth >= 0 ? opt.minPatchWidth : 0.5 * (opt.minEdgeLength > 0 ? opt.minEdgeLength : 0.1 * target);
  // the input's surface curvature per vertex of the preconditioned mesh (empty: not preconditioned)
  std::vector<double> surfaceKappa;
  {  // input edges no longer than twice the target, flat pairs Delaunay (mesh/precondition.h),
     // in the patches that need cuts (only there do curves follow input edges that are not
     // features): a first segmentation of the input finds them
    PreconditionOptions po;
    surf.g = F::buildEdgeGraph(in);
    surf.preconditioned = false;
    F::FeatureOptions f0 = fo;
    f0.featureEdges = userFeatures;
    surf.seg = F::segment(surf.g, f0, progress.fn);
    std::vector<uint8_t> cutPatch(surf.seg.patches.size(), 0);
    for (uint32_t e = 0; e < surf.g.edgeCount(); ++e)
      if (surf.seg.edgeKind[e] == F::EdgeKind::Cut)
        for (uint32_t f : surf.g.edgeFaces[e])
          if (f != F::kNone) cutPatch[surf.seg.facePatch[f]] = 1;
    po.faceMask.resize(in.triangleCount());
    for (uint32_t f = 0; f < in.triangleCount(); ++f) po.faceMask[f] = cutPatch[surf.seg.facePatch[f]];
    po.maxNewVertices = std::max<size_t>(200000, 2 * in.vertexCount());
    // a tiny target on a big surface must not split without end: no more new vertices than
    // the budget (the output limits are checked once the sizing is known)
    po.maxEdgeLength = target > 0 ? std::max(kPreconditionEdgeFactor * target, std::sqrt(area / (0.4 * double(po.maxNewVertices)))) : 0.0;
    // the creases found on the input, kept as they are on the preconditioned mesh (the crease
    // tests look at neighbourhoods, which the splits change)
    std::vector<std::array<uint32_t, 2>> creases = userFeatures;
    for (uint32_t e = 0; e < surf.g.edgeCount(); ++e)
      if (surf.seg.edgeKind[e] == F::EdgeKind::Feature) creases.push_back(surf.g.edgeVerts[e]);
    const Stage segment = clock.enter(Stage::Precondition);
    surf.pre = precondition(in, creases, po);
    clock.enter(segment);
    // no patch needs cuts, so nothing was changed: the segmentation of the input stands
    if (surf.pre.splits > 0 || surf.pre.flips > 0) {
      // the surface's curvature from the input as given (features/sizing.h), carried to the
      // split points (each the larger of its edge's two ends): the precondition's splits
      // depend on the target, and short split edges would change the estimate
      surfaceKappa = F::surfaceCurvature(surf.g);
      surfaceKappa.resize(surf.pre.mesh.vertexCount(), 0.0);
      for (size_t v = in.vertexCount(); v < surfaceKappa.size(); ++v)
        surfaceKappa[v] = std::max(surfaceKappa[surf.pre.parents[v][0]], surfaceKappa[surf.pre.parents[v][1]]);
      fo.featureEdges = surf.pre.protectedEdges;
      fo.detectCreases = false;
      surf.g = F::buildEdgeGraph(surf.pre.mesh);
      surf.preconditioned = true;
      const uint32_t dropped = surf.seg.droppedFeatureEdges;
      surf.seg = F::segment(surf.g, fo, progress.fn);
      surf.seg.droppedFeatureEdges = dropped;
    }
  }
  F::SizingOptions so;
  double splitFloor = 0;  // error-driven: the smallest edge of the target (else the sizing's)
  so.targetEdgeLength = opt.targetEdgeLength;
  so.targetEdgeLengthRel = opt.targetEdgeLengthRel;
  so.chordTolerance = opt.chordTolerance;
  so.chordToleranceRel = opt.chordToleranceRel;
  so.gradation = opt.gradation;
  so.minEdgeLength = opt.minEdgeLength;
  so.maxEdgeLength = opt.maxEdgeLength;
  so.coneTips = opt.coneTips;
  if (errorDriven(opt)) {
    // error-driven (remesh/max_error.h): the chord tolerance and the curvature set the sizes, up
    // to a tenth of the diagonal where the surface is flat, down to a tenth of the target or the
    // tolerance, the smaller: around a spike tip off the curves (man's hair) edges of length h cut
    // about h/2 off it, which no tighter tolerance mends once h is held at a tenth of the target
    // (the distance stayed 1.11e-3 at four tolerances). The refinement's segment splits keep
    // their floor at the target's tenth (Surface::splitFloorLength).
    so.targetEdgeLength = kErrorDrivenMaxSizeRel * diagonal;
    so.maxEdgeLength = opt.maxEdgeLength > 0 ? opt.maxEdgeLength : so.targetEdgeLength;
    splitFloor = opt.minEdgeLength > 0 ? opt.minEdgeLength : 0.1 * target;
    so.minEdgeLength = opt.minEdgeLength > 0 ? opt.minEdgeLength : std::min(splitFloor, opt.chordTolerance > 0 ? opt.chordTolerance : INFINITY);
    // the sizes given per vertex are honoured down to the sizing's own floor: the error-driven
    // search cuts them where an attempt was too far (a spike's tip may need edges below the
    // tolerance)
    if (opt.minEdgeLength <= 0 && !opt.vertexSizing.empty())
      so.minEdgeLength = std::min(so.minEdgeLength, *std::min_element(opt.vertexSizing.begin(), opt.vertexSizing.end()));
  }
  so.surfaceKappa = std::move(surfaceKappa);
  if (surf.pre.splits > 0) so.firstSplitVertex = uint32_t(in.vertexCount());
  if (!opt.vertexSizing.empty()) {
    if (opt.vertexSizing.size() != input.vertexCount())
      fail(Code::InvalidArgument, Stage::CurveMesh, "vertexSizing needs one value per input vertex");
    so.vertexSizing.resize(surf.g.vertexCount);
    for (size_t v = 0; v < so.vertexSizing.size(); ++v)
      so.vertexSizing[v] = v < in.vertexCount() ? opt.vertexSizing[surf.vm.vertexToInput[v]]
                                                : 0.5 * (so.vertexSizing[surf.pre.parents[v][0]] + so.vertexSizing[surf.pre.parents[v][1]]);
  }
  surf.sizing = F::computeSizing(surf.g, surf.seg, so);
  surf.splitFloorLength = splitFloor > 0 ? std::max(splitFloor, 1e-5 * surf.sizing.diagonal) : surf.sizing.minLength;
  {  // output size and memory limits, before the heavy work (remesh/limits.h)
    const OutputEstimate est = estimateOutput(surf.g, surf.seg, surf.sizing);
    rep.estimatedTriangles = est.triangles;
    checkOutputEstimate(est, opt);
  }
  rep.targetEdgeLength = surf.sizing.target;
  surf.chordTolerance = opt.chordTolerance >= 0 ? opt.chordTolerance : opt.chordToleranceRel * surf.sizing.diagonal;
  return surf;
}

}  // namespace conformesh::pipeline
