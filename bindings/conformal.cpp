// conformesh — embind glue, conformal flattening: flatten (src/conformal/flatten.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cmath>
#include <string>
#include <vector>

#include "binding_util.h"
#include "conformal/flatten.h"
#include "conformesh.h"
#include "core/constants.h"

using namespace emscripten;
using namespace conformesh;

namespace {

BoundaryCondition boundaryOption(const val& o) {
  if (o.isUndefined() || o.isNull()) return BoundaryCondition::Circle;
  val b = o["boundary"];
  if (b.isUndefined() || b.isNull()) return BoundaryCondition::Circle;
  if (!b.isString()) fail(Code::InvalidArgument, Stage::Flatten, "boundary must be 'circle', 'free' or 'corners'");
  const std::string s = b.as<std::string>();
  if (s == "circle") return BoundaryCondition::Circle;
  if (s == "free") return BoundaryCondition::Free;
  if (s == "corners") return BoundaryCondition::Corners;
  fail(Code::InvalidArgument, Stage::Flatten, "boundary must be 'circle', 'free' or 'corners', not '" + s + "'");
}

val reportToJs(const FlattenReport& R, size_t corners) {
  val r = val::object();
  r.set("iterations", R.iterations);
  r.set("maxCurvatureError", R.maxCurvatureError);
  r.set("residuals", bindings::typedArrayCopy(R.residuals));
  r.set("flips", double(R.flips));
  r.set("euclideanFlips", double(R.euclideanFlips));
  r.set("seconds", R.seconds);
  r.set("secondsFlow", R.secondsFlow);
  r.set("secondsLayout", R.secondsLayout);
  r.set("secondsOverlay", R.secondsOverlay);
  r.set("gaussBonnetError", R.gaussBonnetError);
  r.set("invertedTriangles", R.invertedTriangles);
  r.set("boundaryCrossings", R.boundaryCrossings);
  r.set("layoutLengthError", R.layoutLengthError);
  r.set("angleDistortionMean", R.angleDistortionMean);
  r.set("angleDistortionMax", R.angleDistortionMax);
  r.set("inputTrianglesInvertedInUv", R.inputTrianglesInvertedInUv);
  r.set("areaDistortionMin", R.areaDistortionMin);
  r.set("areaDistortionMax", R.areaDistortionMax);
  r.set("areaDistortionRange", R.areaDistortionRange);
  r.set("overlayCrossings", double(R.overlayCrossings));
  r.set("boundaryLoops", R.boundaryLoops);
  r.set("corners", double(corners));
  return r;
}

//! flatten(positions, triangles, options, progress)
//!   -> {ok, value: {uv, u, layout: {positions, triangles}, boundaryLoops: Uint32Array[], report}}
//! Options: boundary ('circle' | 'free' | 'corners'), cornerAngle (degrees, corners mode:
//! boundary vertices whose 3D angle differs from 180° by more than this keep their angle),
//! flips, tolerance, maxIterations, balanceMobius, requireValidLayout.
val flattenJs(val positions, val triangles, val options, val progress) {
  return bindings::guarded(Stage::Flatten, [&] {
    MeshBuffers mesh = bindings::meshFromJs(positions, triangles, val::undefined());
    FlattenOptions o;
    o.boundary = boundaryOption(options);
    o.flips = bindings::boolOption(options, "flips", o.flips, Stage::Flatten);
    o.tolerance = bindings::numberOption(options, "tolerance", o.tolerance, Stage::Flatten, 1e-15, 1);
    o.maxIterations = int(bindings::integerOption(options, "maxIterations", o.maxIterations, Stage::Flatten, 1, 10000));
    o.balanceMobius = bindings::boolOption(options, "balanceMobius", o.balanceMobius, Stage::Flatten);
    o.requireValidLayout = bindings::boolOption(options, "requireValidLayout", o.requireValidLayout, Stage::Flatten);
    const double cornerDeg = bindings::numberOption(options, "cornerAngle", 30.0, Stage::Flatten, 1e-9, 179.999999);
    if (o.boundary == BoundaryCondition::Corners) o.corners = detectCorners(mesh, cornerDeg * kPi / 180.0);
    o.pullback = false;  // the pull-back structure is not exposed to JS
    FlatPatch P = flatten(mesh, o, bindings::progressFromJs(progress));
    val out = val::object();
    out.set("uv", bindings::typedArrayCopy(P.uv));
    out.set("u", bindings::typedArrayCopy(P.u));
    out.set("layout", bindings::meshToJs(P.layout));
    val loops = val::array();
    for (const std::vector<uint32_t>& loop : P.boundaryLoops) loops.call<void>("push", bindings::typedArrayCopy(loop));
    out.set("boundaryLoops", loops);
    out.set("report", reportToJs(P.report, o.corners.size()));
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_conformal) { function("flatten", &flattenJs); }
