// conformesh — embind glue, core: the status and stage tables, version, heap statistics.
//
// One glue file per area (module.cpp core, mesh_io.cpp, topology.cpp, ...). Every exported
// function that can fail returns {ok, value} / {ok: false, code, name, stage, message} through
// bindings::guarded (binding_util.h); the TypeScript facade (bindings/src) turns failures into
// ConformeshError. See docs/BINDINGS.md for how to bind a new library function.
#include <emscripten/bind.h>
#include <emscripten/heap.h>
#include <emscripten/val.h>
#include <malloc.h>

#include <string>
#include <vector>

#include "binding_util.h"
#include "conformesh.h"

using namespace emscripten;
using namespace conformesh;

namespace {

//! The status table, for the TypeScript side: [{code, name, fatal, meaning}, ...].
val statusTable() {
  val rows = val::array();
  for (int i = 0; i < codeCount(); ++i) {
    Code c = codeAt(i);
    val row = val::object();
    row.set("code", int(c));
    row.set("name", std::string(codeName(c)));
    row.set("fatal", codeIsFatal(c));
    row.set("meaning", std::string(codeMeaning(c)));
    rows.call<void>("push", row);
  }
  return rows;
}

//! The stage table (conformesh/stages.h), in its order: [{stage, name, key, label, weight, timed, lo,
//! hi}, ...] with the numeric value, the report name ("curve-mesh"), the report's seconds key
//! ("curveMesh"), the label for people, the progress weight, whether remesh() times it, and its
//! interval of a remesh's overall progress.
val stageTable() {
  val rows = val::array();
  for (int i = 0; i < stageCount(); ++i) {
    const Stage s = Stage(i);
    const StageInterval interval = progressInterval(s);
    val row = val::object();
    row.set("stage", i);
    row.set("name", std::string(stageName(s)));
    row.set("key", std::string(stageKey(s)));
    row.set("label", std::string(stageLabel(s)));
    row.set("weight", stageWeight(s));
    row.set("timed", isRemeshStage(s));
    row.set("lo", interval.lo);
    row.set("hi", interval.hi);
    rows.call<void>("push", row);
  }
  return rows;
}

std::string version() { return CONFORMESH_VERSION; }

//! {used, heapSize}: bytes currently allocated by malloc, and the size of the WASM memory. For
//! leak tests (the memory itself never shrinks; `used` must come back to where it was).
val heapStats() {
  struct mallinfo mi = mallinfo();
  val out = val::object();
  out.set("used", double(unsigned(mi.uordblks)));
  out.set("heapSize", double(emscripten_get_heap_size()));
  return out;
}

//! Self-test of the progress bridge every long-running binding uses (progressFromJs here,
//! progress.ts in the facade): reports `steps` fractions i/steps (stage Api) and stops with
//! Cancelled as soon as the callback returns false. Returns the number of reports made.
val progressSelfTest(int steps, val callback) {
  return bindings::guarded(Stage::Api, [&] {
    if (steps < 1 || steps > 1000000) fail(Code::InvalidArgument, Stage::Api, "steps must be in [1, 1e6]");
    ProgressFn progress = bindings::progressFromJs(callback);
    std::vector<double> scratch(1024);  // something to free when cancelled
    for (int i = 1; i <= steps; ++i) {
      scratch[size_t(i) % scratch.size()] = i;
      if (progress && !progress(Stage::Api, double(i) / steps))
        fail(Code::Cancelled, Stage::Api, "cancelled by the progress callback at step " + std::to_string(i));
    }
    return val(steps);
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_core) {
  function("statusTable", &statusTable);
  function("stageTable", &stageTable);
  function("version", &version);
  function("heapStats", &heapStats);
  function("progressSelfTest", &progressSelfTest);
}
