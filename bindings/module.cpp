// conformesh — embind glue. Every exported function catches conformesh::Error (and anything
// else) and turns it into a JS Error whose message starts with "CONFORMESH:<code>:<stage>:", which
// the TypeScript facade turns into a ConformeshError.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <string>

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

std::string version() { return CONFORMESH_VERSION; }

}  // namespace

EMSCRIPTEN_BINDINGS(conformesh_core) {
  function("statusTable", &statusTable);
  function("version", &version);
}
