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

// A report field's JS value, by its C++ type (the rows of CONFORMESH_REMESH_REPORT).
val toJs(double v) { return val(v); }
val toJs(size_t v) { return val(double(v)); }
val toJs(uint32_t v) { return val(double(v)); }
val toJs(int v) { return val(v); }
val toJs(bool v) { return val(v); }
val toJs(const std::vector<uint32_t>& v) { return bindings::typedArrayCopy(v); }
val toJs(const std::vector<std::string>& v) { return bindings::stringArray(v); }
val toJs(const std::vector<int>& v) {
  val a = val::array();
  for (int k : v) a.call<void>("push", k);
  return a;
}
val toJs(const std::vector<ExemptCorner>& corners) {
  val a = val::array();
  for (const ExemptCorner& c : corners) {
    val e = val::object();
#define CONFORMESH_X(type, name, init) e.set(#name, toJs(c.name));
    CONFORMESH_EXEMPT_CORNER(CONFORMESH_X)
#undef CONFORMESH_X
    a.call<void>("push", e);
  }
  return a;
}
val toJs(const StageSeconds& t) {
  val s = val::object();
  for (Stage st : kRemeshStages) s.set(stageKey(st), *t.of(st));
  s.set("total", t.total);
  return s;
}

val reportToJs(const RemeshReport& r) {
  val o = val::object();
#define CONFORMESH_X(type, name, init) o.set(#name, toJs(r.name));
  CONFORMESH_REMESH_REPORT(CONFORMESH_X)
#undef CONFORMESH_X
  return o;
}

// An option from the JS options object, by its C++ type (the rows of CONFORMESH_REMESH_OPTIONS):
// InvalidArgument when it has the wrong type or lies outside [lo, hi].
void readOption(const val& options, const char* name, double& v, double lo, double hi) {
  v = bindings::numberOption(options, name, v, Stage::Api, lo, hi);
}
void readOption(const val& options, const char* name, int& v, double lo, double hi) {
  v = int(bindings::integerOption(options, name, v, Stage::Api, lo, hi));
}
//! Counts beyond size_t (32 bits here) saturate; 0 passes through for remesh to reject (a limit
//! of 0 is InvalidArgument, never "unlimited").
void readOption(const val& options, const char* name, size_t& v, double lo, double hi) {
  const double d = bindings::integerOption(options, name, double(v), Stage::Api, lo, hi);
  v = d >= double(SIZE_MAX) ? SIZE_MAX : size_t(d);
}
void readOption(const val& options, const char* name, bool& v, double, double) {
  v = bindings::boolOption(options, name, v, Stage::Api);
}
void readOption(const val& options, const char* name, Boundary& v, double, double) {
  if (options.isUndefined() || options.isNull() || options[name].isUndefined() || options[name].isNull()) return;
  const val b = options[name];
  if (!b.isString() || !parseBoundary(b.as<std::string>(), v))
    fail(Code::InvalidArgument, Stage::Api, "boundary must be 'free', 'corners' or 'circle'");
}

// The kind and default of an option as the package reads them (remeshSchema).
const char* kindOf(double) { return "number"; }
const char* kindOf(int) { return "integer"; }
const char* kindOf(size_t) { return "count"; }
const char* kindOf(bool) { return "boolean"; }
const char* kindOf(Boundary) { return "boundary"; }
val defaultOf(double v) { return val(v); }
val defaultOf(int v) { return val(v); }
val defaultOf(size_t v) { return val(double(v)); }
val defaultOf(bool v) { return val(v); }
val defaultOf(Boundary v) { return val(std::string(boundaryKey(v))); }

//! The option and report tables (conformesh/remesh_schema.h), for the package: {options: [{name, kind,
//! default, lo, hi, flag, value, help}], report: [name, ...], exemptCorner: [name, ...]}.
val remeshSchema() {
  const RemeshOptions d;
  val options = val::array();
#define CONFORMESH_X(type, name, fallback, lo, hi, flag, value, help) \
  {                                                                   \
    val row = val::object();                                          \
    row.set("name", std::string(#name));                              \
    row.set("kind", std::string(kindOf(d.name)));                    \
    row.set("default", defaultOf(d.name));                            \
    row.set("lo", double(lo));                                        \
    row.set("hi", double(hi));                                        \
    row.set("flag", std::string(flag));                               \
    row.set("value", std::string(value));                             \
    row.set("help", std::string(help));                               \
    options.call<void>("push", row);                                  \
  }
  CONFORMESH_REMESH_OPTIONS(CONFORMESH_X)
#undef CONFORMESH_X
  val report = val::array();
#define CONFORMESH_X(type, name, init) report.call<void>("push", std::string(#name));
  CONFORMESH_REMESH_REPORT(CONFORMESH_X)
#undef CONFORMESH_X
  val corner = val::array();
#define CONFORMESH_X(type, name, init) corner.call<void>("push", std::string(#name));
  CONFORMESH_EXEMPT_CORNER(CONFORMESH_X)
#undef CONFORMESH_X
  val out = val::object();
  out.set("options", options);
  out.set("report", report);
  out.set("exemptCorner", corner);
  return out;
}

//! The pipeline reports a fraction per stage; JS gets one fraction for the whole call: each stage
//! owns the interval of [0, 1] its weight gives it (conformesh/stages.h progressInterval).
ProgressFn overallProgress(ProgressFn stageProgress) {
  if (!stageProgress) return {};
  return [inner = std::move(stageProgress)](Stage s, double f) {
    const StageInterval i = progressInterval(s);
    const double t = f >= 0 && f <= 1 ? f : (f > 1 ? 1.0 : 0.0);
    return inner(s, i.lo + t * (i.hi - i.lo));
  };
}

//! {mesh, report, patches?, patchOfTriangle?, surfacePoints?} of a result (patches with
//! the patches option, surfacePoints when the result has them).
val resultToJs(const RemeshResult& r, bool withPatches) {
  val out = val::object();
  out.set("mesh", bindings::meshToJs(r.mesh));
  out.set("report", reportToJs(r.report));
  if (!r.cornerInputFace.empty()) {
    val points = val::object();
    points.set("face", bindings::typedArrayCopy(r.cornerInputFace));
    points.set("barycentric", bindings::typedArrayCopy(r.cornerBarycentric));
    out.set("surfacePoints", points);
  }
  if (withPatches) {
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
#define CONFORMESH_X(type, name, fallback, lo, hi, flag, value, help) readOption(options, #name, o.name, lo, hi);
    CONFORMESH_REMESH_OPTIONS(CONFORMESH_X)
#undef CONFORMESH_X
    const Stage st = Stage::Api;
    o.vertexSizing = bindings::vectorFromJs<double>(vertexSizing);
    const std::vector<uint32_t> fe = bindings::vectorFromJs<uint32_t>(featureEdges);
    if (fe.size() % 2 != 0) fail(Code::InvalidArgument, st, "featureEdges must hold 2 vertex indices per edge");
    for (size_t i = 0; i + 1 < fe.size(); i += 2) o.featureEdges.push_back({fe[i], fe[i + 1]});
    RemeshResult r = remesh(mesh, o, overallProgress(bindings::progressFromJs(progress)));
    if (!r.status.ok()) {
      if (!r.mesh.triangles.empty()) defective = resultToJs(r, o.patches);
      throw Error(r.status.code, r.status.stage, r.status.message);
    }
    return resultToJs(r, o.patches);
  });
  if (!defective.isUndefined()) answer.set("result", defective);
  return answer;
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_remesh) {
  function("remesh", &remeshJs);
  function("remeshSchema", &remeshSchema);
}
