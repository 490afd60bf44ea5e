// conformesh — helpers shared by every embind glue file (bindings/*.cpp).
//
// The boundary contract (docs/BINDINGS.md):
//  * No C++ exception ever crosses into JS. Every exported function body runs inside `guarded`,
//    which returns a plain JS object: {ok: true, value} on success, or
//    {ok: false, code, name, stage, message} on failure (code/name from the status table in
//    src/core/status.h). The TypeScript facade turns the failure into a ConformeshError. Returning
//    instead of throwing avoids Emscripten 3.1.6's 32-byte stack leak per throw into JS.
//  * Arrays come in as JS typed arrays (the facade guarantees the element type) and are copied
//    into std::vector; arrays go out as copies (`.slice()` of a heap view), never as heap views.
//  * JS callbacks (progress) must not throw: the facade wraps them (see progressFromJs).
#pragma once

#include <emscripten/val.h>

#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "conformesh.h"

namespace conformesh::bindings {

//! {ok: false, code, name, stage, message}.
emscripten::val failure(Code code, Stage stage, const std::string& message);

//! Run `body` (returning emscripten::val) and wrap its value as {ok: true, value}; any exception
//! becomes a failure object: conformesh::Error keeps its code and stage; std::bad_alloc becomes
//! TooLarge (WASM memory is capped at 4 GB); anything else is InternalError in `stage`.
template <class Body>
emscripten::val guarded(Stage stage, Body&& body) noexcept {
  try {
    emscripten::val value = std::forward<Body>(body)();
    emscripten::val out = emscripten::val::object();
    out.set("ok", true);
    out.set("value", value);
    return out;
  } catch (const Error& e) {
    return failure(e.code(), e.stage(), e.what());
  } catch (const std::bad_alloc&) {
    return failure(Code::TooLarge, stage, "out of memory (the WebAssembly heap is limited to 4 GB)");
  } catch (const std::exception& e) {
    return failure(Code::InternalError, stage, std::string("unexpected C++ exception: ") + e.what());
  } catch (...) {
    return failure(Code::InternalError, stage, "unexpected exception of unknown type");
  }
}

//! Copy a JS typed array (or array-like of numbers) into a vector. Elements are converted as by
//! the typed array of T (the facade passes Float64Array / Uint32Array / Uint8Array already).
template <class T>
std::vector<T> vectorFromJs(const emscripten::val& array) {
  return emscripten::convertJSArrayToNumberVector<T>(array);
}

//! A new JS typed array holding a copy of `data` (Float64Array for double, Uint32Array for
//! uint32_t, Uint8Array for uint8_t).
template <class T>
emscripten::val typedArrayCopy(const std::vector<T>& data) {
  return emscripten::val(emscripten::typed_memory_view(data.size(), data.data())).call<emscripten::val>("slice");
}

//! JS array of strings.
emscripten::val stringArray(const std::vector<std::string>& strings);

//! Build MeshBuffers from the arrays the facade passes (uvs may be empty; attributes: undefined
//! or an array of {name, itemSize, perCorner, values: Float64Array}). Throws
//! Error(InvalidArgument, Api) when a length is not a multiple of 3 (positions, triangles), uvs
//! is neither empty nor 2 per vertex, or an attribute's shape is wrong (checkAttributes). Index
//! and coordinate validity is left to the library.
MeshBuffers meshFromJs(const emscripten::val& positions, const emscripten::val& triangles,
                       const emscripten::val& uvs, const emscripten::val& attributes = emscripten::val::undefined());

//! {positions: Float64Array, triangles: Uint32Array, uvs?: Float64Array, attributes?: [{name,
//! itemSize, perCorner, values: Float64Array}]} (copies).
emscripten::val meshToJs(const MeshBuffers& mesh);

//! Option `name` of a JS options object (undefined/null object or field: `fallback`). Throws
//! Error(InvalidArgument, stage) when the field has the wrong type or, for numbers, is not finite
//! or outside [min, max]. The facade passes plain objects with known keys only.
double numberOption(const emscripten::val& options, const char* name, double fallback, Stage stage,
                    double min = -1e308, double max = 1e308);
//! numberOption that also rejects a value with a fractional part (counts, caps).
double integerOption(const emscripten::val& options, const char* name, double fallback, Stage stage,
                     double min = -1e308, double max = 1e308);
bool boolOption(const emscripten::val& options, const char* name, bool fallback, Stage stage);

//! Wrap a JS function (stage: number, fraction: number) => boolean as a ProgressFn; undefined or
//! null gives an empty ProgressFn. The JS function must not throw (the facade's wrapper catches
//! and returns false, which cancels): a JS exception unwinding through C++ frames would skip
//! destructors and leak. In the threaded build only the module's main thread calls it (a report
//! from a pool thread is skipped and means "go on").
ProgressFn progressFromJs(const emscripten::val& callback);

}  // namespace conformesh::bindings
