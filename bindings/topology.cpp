// conformesh — embind glue, validation and topology: meshInfo, validateMesh (src/mesh/topology.h,
// src/mesh/validate.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <string>

#include "binding_util.h"
#include "conformesh.h"
#include "mesh/topology.h"
#include "mesh/validate.h"

using namespace emscripten;
using namespace conformesh;

namespace {

val warningsToJs(const std::vector<ValidationWarning>& warnings) {
  val out = val::array();
  for (const ValidationWarning& w : warnings) {
    val row = val::object();
    row.set("code", std::string(codeName(w.code)));
    row.set("count", double(w.count));
    row.set("message", w.message);
    out.call<void>("push", row);
  }
  return out;
}

ValidateOptions validateOptions(const val& o) {
  ValidateOptions v;
  const double cap = double(size_t(1) << 31);
  v.maxVertices = size_t(bindings::integerOption(o, "maxVertices", double(v.maxVertices), Stage::Validate, 1, cap));
  v.maxTriangles = size_t(bindings::integerOption(o, "maxTriangles", double(v.maxTriangles), Stage::Validate, 1, cap));
  v.dropZeroAreaFaces = bindings::boolOption(o, "dropZeroAreaFaces", v.dropZeroAreaFaces, Stage::Validate);
  v.dropDuplicateFaces = bindings::boolOption(o, "dropDuplicateFaces", v.dropDuplicateFaces, Stage::Validate);
  v.fixOrientation = bindings::boolOption(o, "fixOrientation", v.fixOrientation, Stage::Validate);
  v.splitNonManifoldVertices =
      bindings::boolOption(o, "splitNonManifoldVertices", v.splitNonManifoldVertices, Stage::Validate);
  return v;
}

//! meshInfo(positions, triangles, options) -> {ok, value: MeshInfo}
val meshInfoJs(val positions, val triangles, val options) {
  return bindings::guarded(Stage::Validate, [&] {
    ValidateOptions limits = validateOptions(options);
    MeshInfo info = meshInfo(bindings::meshFromJs(positions, triangles, val::undefined()), limits);
    val out = val::object();
    out.set("vertices", double(info.vertices));
    out.set("faces", double(info.faces));
    out.set("edges", double(info.edges));
    out.set("components", double(info.components));
    out.set("boundaryLoops", double(info.boundaryLoops));
    out.set("euler", double(info.euler));
    out.set("genus", info.genus);
    out.set("nonManifoldEdges", double(info.nonManifoldEdges));
    out.set("nonManifoldVertices", double(info.nonManifoldVertices));
    out.set("degenerateFaces", double(info.degenerateFaces));
    out.set("duplicateFaces", double(info.duplicateFaces));
    out.set("inconsistentFaces", double(info.inconsistentFaces));
    out.set("warnings", warningsToJs(info.warnings));
    return out;
  });
}

//! validateMesh(positions, triangles, uvs, options) -> {ok, value: {mesh, report, vertexToInput, faceToInput}}
val validateMeshJs(val positions, val triangles, val uvs, val options) {
  return bindings::guarded(Stage::Validate, [&] {
    ValidateOptions o = validateOptions(options);
    ValidatedMesh v = validate(bindings::meshFromJs(positions, triangles, uvs), o);
    const ValidationReport& r = v.report;
    val report = val::object();
    report.set("inputVertices", double(r.inputVertices));
    report.set("inputTriangles", double(r.inputTriangles));
    report.set("degenerateFaces", double(r.degenerateFaces));
    report.set("zeroAreaFaces", double(r.zeroAreaFaces));
    report.set("duplicateFaces", double(r.duplicateFaces));
    report.set("flippedFaces", double(r.flippedFaces));
    report.set("splitVertices", double(r.splitVertices));
    report.set("removedVertices", double(r.removedVertices));
    report.set("warnings", warningsToJs(r.warnings));
    val out = val::object();
    out.set("mesh", bindings::meshToJs(v.buffers));
    out.set("report", report);
    out.set("vertexToInput", bindings::typedArrayCopy(v.vertexToInput));
    out.set("faceToInput", bindings::typedArrayCopy(v.faceToInput));
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_topology) {
  function("meshInfo", &meshInfoJs);
  function("validateMesh", &validateMeshJs);
}
