// conformesh — embind glue, the remesh pipeline: remesh (src/remesh/remesh.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "binding_util.h"
#include "conformesh.h"
#include "remesh/remesh.h"

using namespace emscripten;
using namespace conformesh;

namespace {

val reportToJs(const RemeshReport& r) {
  val o = val::object();
  o.set("inputTriangles", double(r.inputTriangles));
  o.set("inputVertices", double(r.inputVertices));
  o.set("triangles", double(r.triangles));
  o.set("vertices", double(r.vertices));
  o.set("minAngle", r.minAngle);
  o.set("maxAngle", r.maxAngle);
  o.set("meanMinAngle", r.meanMinAngle);
  o.set("pctBelow20", r.pctBelow20);
  o.set("pctBelow26", r.pctBelow26);
  o.set("pctBelow30", r.pctBelow30);
  o.set("pctMinAtLeast40", r.pctMinAtLeast40);
  o.set("pctMinAtLeast50", r.pctMinAtLeast50);
  o.set("minAngleOutsideExempt", r.minAngleOutsideExempt);
  o.set("trianglesBelowBoundOutsideExempt", double(r.trianglesBelowBoundOutsideExempt));
  val corners = val::array();
  for (const ExemptCorner& c : r.exemptCorners) {
    val e = val::object();
    e.set("vertex", double(c.inputVertex));
    e.set("outputVertex", double(c.outputVertex));
    e.set("angle", c.angleDeg);
    e.set("triangles", bindings::typedArrayCopy(c.triangles));
    corners.call<void>("push", e);
  }
  o.set("exemptCorners", corners);
  o.set("hausdorffRel", r.hausdorffRel);
  o.set("maxDistanceToInputRel", r.maxDistanceToInputRel);
  o.set("meanEdgeLength", r.meanEdgeLength);
  o.set("targetEdgeLength", r.targetEdgeLength);
  o.set("delaunayFraction", r.delaunayFraction);
  o.set("featureCurves", double(r.featureCurves));
  o.set("featureCurvesKept", double(r.featureCurvesKept));
  o.set("sharpEdges", double(r.sharpEdges));
  o.set("cutEdges", double(r.cutEdges));
  o.set("droppedFeatureEdges", double(r.droppedFeatureEdges));
  o.set("seamEdges", double(r.seamEdges));
  o.set("patches", double(r.patches));
  o.set("curves", double(r.curves));
  o.set("curveSamples", double(r.curveSamples));
  val iters = val::array();
  for (int k : r.flowIterations) iters.call<void>("push", k);
  o.set("flowIterations", iters);
  o.set("patchSplitsForScale", double(r.patchSplitsForScale));
  o.set("conformingRounds", r.conformingRounds);
  o.set("certificateRounds", r.certificateRounds);
  o.set("optimizeMoves", double(r.optimizeMoves));
  o.set("optimizeFlips", double(r.optimizeFlips));
  o.set("repairMoves", double(r.repairMoves));
  o.set("estimatedTriangles", r.estimatedTriangles);
  o.set("topologyPreserved", r.topologyPreserved);
  const StageSeconds& t = r.seconds;
  val s = val::object();
  for (Stage st : kRemeshStages) s.set(stageKey(st), *t.of(st));
  s.set("total", t.total);
  o.set("seconds", s);
  o.set("warnings", bindings::stringArray(r.warnings));
  return o;
}

//! The pipeline reports a fraction per stage; JS gets one fraction for the whole call: each stage
//! owns the interval of [0, 1] its weight gives it (core/stages.h progressInterval).
ProgressFn overallProgress(ProgressFn stageProgress) {
  if (!stageProgress) return {};
  return [inner = std::move(stageProgress)](Stage s, double f) {
    const StageInterval i = progressInterval(s);
    const double t = f >= 0 && f <= 1 ? f : (f > 1 ? 1.0 : 0.0);
    return inner(s, i.lo + t * (i.hi - i.lo));
  };
}

//! {mesh, report, patches?, patchOfTriangle?, surfacePoints?} of a result (patches with
//! returnPatches, surfacePoints when the result has them).
val resultToJs(const RemeshResult& r, bool returnPatches) {
  val out = val::object();
  out.set("mesh", bindings::meshToJs(r.mesh));
  out.set("report", reportToJs(r.report));
  if (!r.cornerInputFace.empty()) {
    val points = val::object();
    points.set("face", bindings::typedArrayCopy(r.cornerInputFace));
    points.set("barycentric", bindings::typedArrayCopy(r.cornerBarycentric));
    out.set("surfacePoints", points);
  }
  if (returnPatches) {
    val patches = val::array();
    for (size_t p = 0; p < r.patches.size(); ++p) {
      const RemeshPatch& rp = r.patches[p];
      val layout = val::object();
      layout.set("uv", bindings::typedArrayCopy(rp.layoutUv));
      layout.set("triangles", bindings::typedArrayCopy(rp.layoutTriangles));
      layout.set("inputFace", bindings::typedArrayCopy(rp.layoutInputFace));
      layout.set("factor", bindings::typedArrayCopy(rp.layoutFactor));
      val refined = val::object();
      refined.set("uv", bindings::typedArrayCopy(rp.uv));
      refined.set("triangles", bindings::typedArrayCopy(rp.triangles));
      refined.set("outputVertex", bindings::typedArrayCopy(rp.outputVertex));
      val e = val::object();
      e.set("id", double(p));
      e.set("layout", layout);
      e.set("refined", refined);
      patches.call<void>("push", e);
    }
    out.set("patches", patches);
    out.set("patchOfTriangle", bindings::typedArrayCopy(r.patchOfTriangle));
  }
  return out;
}

//! remesh(positions, triangles, uvs, attributes, vertexSizing, featureEdges, options, progress)
//!   -> {ok, value: {mesh: {positions, triangles, uvs?, attributes?}, report, surfacePoints?}}
//! A failed RemeshResult (status not Ok) becomes the failure object with its code and stage, and,
//! when it has a mesh (keepDefectiveOutput), the result as `result`.
val remeshJs(val positions, val triangles, val uvs, val attributes, val vertexSizing, val featureEdges, val options, val progress) {
  val defective = val::undefined();
  val answer = bindings::guarded(Stage::Api, [&] {
    MeshBuffers mesh = bindings::meshFromJs(positions, triangles, uvs, attributes);
    RemeshOptions o;
    const Stage st = Stage::Api;
    o.minAngleDeg = bindings::numberOption(options, "minAngle", o.minAngleDeg, st, 0, 34);
    o.targetEdgeLength = bindings::numberOption(options, "targetEdgeLength", o.targetEdgeLength, st, 0);
    o.targetEdgeLengthRel = bindings::numberOption(options, "targetEdgeLengthRel", o.targetEdgeLengthRel, st, 0);
    o.chordTolerance = bindings::numberOption(options, "chordTolerance", o.chordTolerance, st);
    o.chordToleranceRel = bindings::numberOption(options, "chordToleranceRel", o.chordToleranceRel, st, 0);
    o.maxError = bindings::numberOption(options, "maxError", o.maxError, st, 0);
    o.maxErrorRel = bindings::numberOption(options, "maxErrorRel", o.maxErrorRel, st, 0);
    o.gradation = bindings::numberOption(options, "gradation", o.gradation, st, 1);
    o.minEdgeLength = bindings::numberOption(options, "minEdgeLength", o.minEdgeLength, st);
    o.maxEdgeLength = bindings::numberOption(options, "maxEdgeLength", o.maxEdgeLength, st);
    o.featureAngleDeg = bindings::numberOption(options, "featureAngle", o.featureAngleDeg, st, 0, 180);
    o.cornerTurnDeg = bindings::numberOption(options, "cornerTurn", o.cornerTurnDeg, st, 0, 180);
    o.minFeatureLength = bindings::numberOption(options, "minFeatureLength", o.minFeatureLength, st);
    o.minPatchWidth = bindings::numberOption(options, "minPatchWidth", o.minPatchWidth, st);
    o.maxScaleRatio = bindings::numberOption(options, "maxScaleRatio", o.maxScaleRatio, st, 1);
    o.maxCertificateRounds =
        int(bindings::integerOption(options, "maxCertificateRounds", o.maxCertificateRounds, st, 0, 100));
    o.computeHausdorff = bindings::boolOption(options, "computeHausdorff", o.computeHausdorff, st);
    o.optimize = bindings::boolOption(options, "optimize", o.optimize, st);
    o.returnPatches = bindings::boolOption(options, "patches", o.returnPatches, st);
    o.carryAttributes = bindings::boolOption(options, "attributes", o.carryAttributes, st);
    o.returnSurfacePoints = bindings::boolOption(options, "surfacePoints", o.returnSurfacePoints, st);
    o.keepDefectiveOutput = bindings::boolOption(options, "keepDefectiveOutput", o.keepDefectiveOutput, st);
    o.forceTopologyDefect = bindings::boolOption(options, "forceTopologyDefect", o.forceTopologyDefect, st);
    if (!options.isUndefined() && !options.isNull() && !options["boundary"].isUndefined() && !options["boundary"].isNull()) {
      val b = options["boundary"];
      const std::string s = b.isString() ? b.as<std::string>() : std::string();
      if (s == "free") o.boundary = BoundaryCondition::Free;
      else if (s == "corners") o.boundary = BoundaryCondition::Corners;
      else if (s == "circle") o.boundary = BoundaryCondition::Circle;
      else fail(Code::InvalidArgument, st, "boundary must be 'free', 'corners' or 'circle'");
    }
    o.optimizeIterations = int(bindings::integerOption(options, "optimizeIterations", o.optimizeIterations, st, 0, 1000));
    o.optimizeTolerance = bindings::numberOption(options, "optimizeTolerance", o.optimizeTolerance, st, 0);
    // the single-threaded module accepts it and runs on one thread; the threaded one (-pthread) uses it
    o.threads = int(bindings::integerOption(options, "threads", o.threads, st, 0, 1024));
    o.hausdorffSamples =
        size_t(bindings::integerOption(options, "hausdorffSamples", double(o.hausdorffSamples), st, 1, 1e8));
    // limits: 0 passes through and is rejected by remesh (InvalidArgument), never "unlimited";
    // values beyond size_t (32 bits here) saturate
    auto count = [&](const char* name, size_t fallback) {
      const double v = bindings::numberOption(options, name, double(fallback), st, 0, 1e18);
      return v >= double(SIZE_MAX) ? SIZE_MAX : size_t(v);
    };
    o.maxTriangles = count("maxTriangles", o.maxTriangles);
    o.maxVertices = count("maxVertices", o.maxVertices);
    o.maxMemoryBytes = bindings::numberOption(options, "maxMemoryBytes", o.maxMemoryBytes, st, 0);
    o.vertexSizing = bindings::vectorFromJs<double>(vertexSizing);
    const std::vector<uint32_t> fe = bindings::vectorFromJs<uint32_t>(featureEdges);
    if (fe.size() % 2 != 0) fail(Code::InvalidArgument, st, "featureEdges must hold 2 vertex indices per edge");
    for (size_t i = 0; i + 1 < fe.size(); i += 2) o.featureEdges.push_back({fe[i], fe[i + 1]});
    RemeshResult r = remesh(mesh, o, overallProgress(bindings::progressFromJs(progress)));
    if (!r.status.ok()) {
      if (!r.mesh.triangles.empty()) defective = resultToJs(r, o.returnPatches);
      throw Error(r.status.code, r.status.stage, r.status.message);
    }
    return resultToJs(r, o.returnPatches);
  });
  if (!defective.isUndefined()) answer.set("result", defective);
  return answer;
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_remesh) { function("remesh", &remeshJs); }
