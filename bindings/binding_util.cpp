#include "binding_util.h"

#include "mesh/mesh_attributes.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#ifdef __EMSCRIPTEN_PTHREADS__
#include <emscripten/threading.h>
#endif

namespace conformesh::bindings {

using emscripten::val;

val failure(Code code, Stage stage, const std::string& message) {
  val out = val::object();
  out.set("ok", false);
  out.set("code", int(code));
  out.set("name", std::string(codeName(code)));
  out.set("stage", std::string(stageName(stage)));
  out.set("message", message);
  return out;
}

val stringArray(const std::vector<std::string>& strings) {
  val out = val::array();
  for (const std::string& s : strings) out.call<void>("push", s);
  return out;
}

MeshBuffers meshFromJs(const val& positions, const val& triangles, const val& uvs, const val& attributes) {
  MeshBuffers mesh;
  mesh.positions = vectorFromJs<double>(positions);
  mesh.triangles = vectorFromJs<uint32_t>(triangles);
  if (!uvs.isUndefined() && !uvs.isNull()) mesh.uvs = vectorFromJs<double>(uvs);
  if (mesh.positions.size() % 3 != 0)
    fail(Code::InvalidArgument, Stage::Api,
         "positions has " + std::to_string(mesh.positions.size()) + " numbers, not a multiple of 3 (x y z per vertex)");
  if (mesh.triangles.size() % 3 != 0)
    fail(Code::InvalidArgument, Stage::Api,
         "triangles has " + std::to_string(mesh.triangles.size()) + " indices, not a multiple of 3");
  if (!mesh.uvs.empty() && mesh.uvs.size() != 2 * mesh.vertexCount())
    fail(Code::InvalidArgument, Stage::Api,
         "uvs has " + std::to_string(mesh.uvs.size()) + " numbers; expected 2 per vertex (" +
             std::to_string(2 * mesh.vertexCount()) + ") or none");
  if (!attributes.isUndefined() && !attributes.isNull()) {
    const size_t n = attributes["length"].as<size_t>();
    for (size_t i = 0; i < n; ++i) {
      const val a = attributes[i];
      MeshAttribute m{a["name"].as<std::string>(), a["itemSize"].as<uint32_t>(), a["perCorner"].as<bool>(),
                      vectorFromJs<double>(a["values"])};
      mesh.attributes.push_back(std::move(m));
    }
    checkAttributes(mesh, Stage::Api);
  }
  return mesh;
}

val meshToJs(const MeshBuffers& mesh) {
  val out = val::object();
  out.set("positions", typedArrayCopy(mesh.positions));
  out.set("triangles", typedArrayCopy(mesh.triangles));
  if (!mesh.uvs.empty()) out.set("uvs", typedArrayCopy(mesh.uvs));
  if (!mesh.attributes.empty()) {
    val list = val::array();
    for (const MeshAttribute& a : mesh.attributes) {
      val o = val::object();
      o.set("name", a.name);
      o.set("itemSize", a.components);
      o.set("perCorner", a.perCorner);
      o.set("values", typedArrayCopy(a.values));
      list.call<void>("push", o);
    }
    out.set("attributes", list);
  }
  return out;
}

namespace {
val field(const val& options, const char* name) {
  if (options.isUndefined() || options.isNull()) return val::undefined();
  return options[name];
}
}  // namespace

namespace {
std::string formatNumber(double d) {
  char buf[32];
  for (int digits = 6; digits <= 17; ++digits) {  // the shortest form that reads back as d
    std::snprintf(buf, sizeof buf, "%.*g", digits, d);
    if (std::strtod(buf, nullptr) == d) break;
  }
  return buf;
}
}  // namespace

double numberOption(const val& options, const char* name, double fallback, Stage stage, double min, double max) {
  val v = field(options, name);
  if (v.isUndefined() || v.isNull()) return fallback;
  if (!v.isNumber()) fail(Code::InvalidArgument, stage, std::string("option ") + name + " must be a number");
  double d = v.as<double>();
  if (std::isfinite(d) && d >= min && d <= max) return d;
  std::string range = min <= -1e308 ? (max >= 1e308 ? std::string("finite") : "<= " + formatNumber(max))
                      : max >= 1e308 ? ">= " + formatNumber(min)
                                     : "in [" + formatNumber(min) + ", " + formatNumber(max) + "]";
  fail(Code::InvalidArgument, stage, std::string("option ") + name + " = " + formatNumber(d) + " must be " + range);
}

double integerOption(const val& options, const char* name, double fallback, Stage stage, double min, double max) {
  const double d = numberOption(options, name, fallback, stage, min, max);
  if (d != std::floor(d))
    fail(Code::InvalidArgument, stage, std::string("option ") + name + " = " + formatNumber(d) + " must be an integer");
  return d;
}

bool boolOption(const val& options, const char* name, bool fallback, Stage stage) {
  val v = field(options, name);
  if (v.isUndefined() || v.isNull()) return fallback;
  if (!v.isTrue() && !v.isFalse()) fail(Code::InvalidArgument, stage, std::string("option ") + name + " must be true or false");
  return v.isTrue();
}

ProgressFn progressFromJs(const val& callback) {
  if (callback.isUndefined() || callback.isNull()) return {};
  // A JS value lives on the module's main thread: copies of the ProgressFn share one handle (no
  // JS call to copy it), and a report from a pool thread (threaded build) is skipped, not a crash.
  auto fn = std::make_shared<val>(callback);
  return [fn](Stage stage, double fraction) {
#ifdef __EMSCRIPTEN_PTHREADS__
    if (!emscripten_is_main_runtime_thread()) return true;
#endif
    return (*fn)(int(stage), fraction).as<bool>();
  };
}

}  // namespace conformesh::bindings
