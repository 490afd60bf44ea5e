// conformesh — embind glue, mesh files: readMesh / writeMesh (src/mesh/mesh_io.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cmath>
#include <string>

#include "binding_util.h"
#include "conformesh.h"
#include "mesh/mesh_io.h"

using namespace emscripten;
using namespace conformesh;

namespace {

//! A format name from JS: "" or "auto" is Auto; a name formatFromName does not know is an error.
MeshFormat formatArg(const std::string& name, Stage stage) {
  if (name.empty() || name == "auto") return MeshFormat::Auto;
  MeshFormat f = formatFromName(name);
  if (f == MeshFormat::Auto)
    fail(Code::InvalidArgument, stage,
         "unknown mesh format '" + name + "' (obj, off, stl, stl-ascii, ply, ply-ascii, ply-be)");
  return f;
}

//! readMesh(bytes: Uint8Array, format, fileName, weldTolerance, readUvs, readAttributes)
//!   -> {ok, value: {positions, triangles, uvs?, attributes?, format, warnings}}
val readMeshJs(val bytes, std::string format, std::string fileName, double weldTolerance, bool readUvs, bool readAttributes) {
  return bindings::guarded(Stage::Read, [&] {
    ReadOptions options;
    options.format = formatArg(format, Stage::Read);
    options.fileName = fileName;
    if (!(weldTolerance >= 0.0) || !std::isfinite(weldTolerance))
      fail(Code::InvalidArgument, Stage::Read, "weldTolerance must be a finite number >= 0");
    options.weldTolerance = weldTolerance;
    options.readUvs = readUvs;
    options.readAttributes = readAttributes;
    std::vector<uint8_t> data = bindings::vectorFromJs<uint8_t>(bytes);
    ReadResult result = readMesh(data, options);
    data = {};
    val out = bindings::meshToJs(result.mesh);
    out.set("format", std::string(formatName(result.format)));
    out.set("warnings", bindings::stringArray(result.warnings));
    return out;
  });
}

//! writeMesh(positions, triangles, uvs, attributes, format, writeUvs, writeAttributes) -> {ok, value: Uint8Array}
val writeMeshJs(val positions, val triangles, val uvs, val attributes, std::string format, bool writeUvs, bool writeAttributes) {
  return bindings::guarded(Stage::Write, [&] {
    MeshFormat f = formatArg(format, Stage::Write);
    if (f == MeshFormat::Auto)
      fail(Code::InvalidArgument, Stage::Write, "writeMesh needs a format (obj, off, stl, stl-ascii, ply, ply-ascii)");
    MeshBuffers mesh = bindings::meshFromJs(positions, triangles, uvs, attributes);
    WriteOptions options;
    options.writeUvs = writeUvs;
    options.writeAttributes = writeAttributes;
    return bindings::typedArrayCopy(writeMesh(mesh, f, options));
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_mesh_io) {
  function("readMesh", &readMeshJs);
  function("writeMesh", &writeMeshJs);
}
