// conformesh — embind glue, planar meshing: refine2d, readPoly (src/planar/refine.h, poly_io.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <string>
#include <vector>

#include "binding_util.h"
#include "conformesh.h"
#include "planar/poly_io.h"
#include "planar/refine.h"

using namespace emscripten;
using namespace conformesh;

namespace {

//! {points, segments, segmentMarkers?, holes} of a PSLG (copies).
val pslgToJs(const planar::Pslg& p) {
  val out = val::object();
  out.set("points", bindings::typedArrayCopy(p.points));
  out.set("segments", bindings::typedArrayCopy(p.segments));
  out.set("holes", bindings::typedArrayCopy(p.holes));
  if (!p.segmentMarkers.empty()) out.set("segmentMarkers", bindings::typedArrayCopy(p.segmentMarkers));
  return out;
}

//! refine2d(points, segments, segmentMarkers, holes, options, progress)
//!   -> {ok, value: {vertices, triangles, edges, edgeSegment, edgeMarker, vertexSegment,
//!       vertexParam, minAngle, exemptTriangles, insertions, segmentSplits, rejected, seconds,
//!       status, message}}
//! IterationLimit (maxInsertions reached) comes back as the value with its `status`; the facade
//! throws it with the value attached (callRaw, bindings/src/raw.ts).
val refine2dJs(val points, val segments, val segmentMarkers, val holes, val options, val progress) {
  return bindings::guarded(Stage::Refine, [&] {
    planar::Pslg pslg;
    pslg.points = bindings::vectorFromJs<double>(points);
    pslg.segments = bindings::vectorFromJs<uint32_t>(segments);
    pslg.segmentMarkers = bindings::vectorFromJs<int32_t>(segmentMarkers);
    pslg.holes = bindings::vectorFromJs<double>(holes);
    if (pslg.points.size() % 2 != 0)
      fail(Code::InvalidArgument, Stage::Refine, "points must hold 2 numbers (x, y) per vertex");
    if (pslg.segments.size() % 2 != 0)
      fail(Code::InvalidArgument, Stage::Refine, "segments must hold 2 vertex indices per segment");
    if (pslg.holes.size() % 2 != 0)
      fail(Code::InvalidArgument, Stage::Refine, "holes must hold 2 numbers (x, y) per hole seed");
    if (!pslg.segmentMarkers.empty() && pslg.segmentMarkers.size() * 2 != pslg.segments.size())
      fail(Code::InvalidArgument, Stage::Refine, "segmentMarkers must be empty or hold one marker per segment");

    planar::RefineOptions o;
    // ranges are checked by refinePslg (the same messages as the native CLI)
    o.minAngleDeg = bindings::numberOption(options, "minAngle", o.minAngleDeg, Stage::Refine);
    o.maxArea = bindings::numberOption(options, "maxArea", o.maxArea, Stage::Refine);
    o.maxEdge = bindings::numberOption(options, "maxEdge", o.maxEdge, Stage::Refine);
    if (o.maxArea > 0 && o.maxEdge > 0)
      fail(Code::InvalidArgument, Stage::Refine, "give maxArea or maxEdge, not both");
    o.maxInsertions = size_t(bindings::integerOption(options, "maxInsertions", double(o.maxInsertions), Stage::Refine, 0,
                                                    9007199254740992.0));
    o.offcenters = bindings::boolOption(options, "offcenters", o.offcenters, Stage::Refine);
    o.diametralLens = bindings::boolOption(options, "diametralLens", o.diametralLens, Stage::Refine);
    o.cdt.convexHull = bindings::boolOption(options, "convexHull", o.cdt.convexHull, Stage::Refine);
    o.cdt.holesByOrientation =
        bindings::boolOption(options, "holesByOrientation", o.cdt.holesByOrientation, Stage::Refine);
    o.progress = bindings::progressFromJs(progress);

    planar::RefineResult r = planar::refinePslg(pslg, o);
    const planar::PlanarMesh& m = r.mesh;
    val out = val::object();
    out.set("vertices", bindings::typedArrayCopy(m.points));
    out.set("triangles", bindings::typedArrayCopy(m.triangles));
    out.set("edges", bindings::typedArrayCopy(m.edges));
    out.set("edgeSegment", bindings::typedArrayCopy(m.edgeSegment));
    out.set("edgeMarker", bindings::typedArrayCopy(m.edgeMarker));
    out.set("vertexSegment", bindings::typedArrayCopy(m.vertexSegment));
    out.set("vertexParam", bindings::typedArrayCopy(m.vertexParam));
    out.set("minAngle", r.minAngleDeg);
    out.set("exemptTriangles", double(r.exemptTriangles));
    out.set("insertions", double(r.insertions));
    out.set("segmentSplits", double(r.segmentSplits));
    out.set("rejected", double(r.rejected));
    out.set("seconds", r.seconds);
    out.set("status", std::string(codeName(r.status.code)));
    out.set("message", r.status.message);
    return out;
  });
}

//! readPoly(bytes) -> {ok, value: {points, segments, segmentMarkers?, holes}}
val readPolyJs(val bytes) {
  return bindings::guarded(Stage::Read, [&] { return pslgToJs(planar::readPoly(bindings::vectorFromJs<uint8_t>(bytes))); });
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_planar) {
  function("refine2d", &refine2dJs);
  function("readPoly", &readPolyJs);
}
