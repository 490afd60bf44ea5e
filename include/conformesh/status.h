// conformesh — status codes and the error type (the stages: conformesh/stages.h).
//
// The table below is the ONE definition of the status codes. C++ uses it through the
// enum `Code`; the WASM module exports it (`statusTable()`), and the TypeScript union
// in bindings/ is checked against that export by a test.
#pragma once

#include <stdexcept>
#include <string>

#include "conformesh/stages.h"

namespace conformesh {

// X(name, numeric value, fatal?, one-line meaning)
#define CONFORMESH_STATUS_TABLE(X)                                                              \
  X(Ok, 0, false, "success")                                                                    \
  X(EmptyMesh, 1, true, "the input has no vertices or no faces")                                \
  X(ParseError, 2, true, "the bytes are not a valid mesh file (see line / byte offset)")       \
  X(IndexOutOfRange, 3, true, "a face refers to a vertex that does not exist")                  \
  X(NonFiniteCoordinate, 4, true, "a coordinate is NaN or infinite")                            \
  X(DegenerateFace, 5, false, "a face has repeated vertices or zero area (dropped, warning)")   \
  X(NonManifoldEdge, 6, true, "an edge is shared by more than two faces")                       \
  X(NonManifoldVertex, 7, true, "a vertex's faces do not form a single fan (bow-tie)")          \
  X(InconsistentOrientation, 8, false, "neighbouring faces disagree on orientation (repaired)") \
  X(TooLarge, 9, true, "the input or the requested output exceeds the size limits")             \
  X(InvalidArgument, 10, true, "an option or argument is out of range")                         \
  X(Cancelled, 11, true, "the progress callback asked to stop")                                 \
  X(IterationLimit, 12, true, "an iterative loop hit its hard cap before converging")           \
  X(NotConverged, 13, true, "a solver did not reach its tolerance")                             \
  X(InvalidPslg, 14, true, "the planar straight-line graph is invalid (crossing segments ...)") \
  X(InvalidTopology, 15, true, "the mesh has the wrong topology for this operation")            \
  X(NumericalFailure, 16, true, "a numerical step failed (singular matrix, inverted layout)")    \
  X(IoError, 17, true, "a file could not be read or written")                                   \
  X(InternalError, 18, true, "a bug: an internal invariant does not hold")

enum class Code : int {
#define CONFORMESH_X(name, value, fatal, text) name = value,
  CONFORMESH_STATUS_TABLE(CONFORMESH_X)
#undef CONFORMESH_X
};

//! Name of a code as in the table ("NonManifoldEdge"); "Unknown" for values not in it.
const char* codeName(Code c);
//! The table's one-line meaning of a code.
const char* codeMeaning(Code c);
//! Whether the code stops the pipeline (true) or is repaired and reported as a warning.
bool codeIsFatal(Code c);
//! Number of rows in the status table.
int codeCount();
//! Row i of the status table (0 <= i < codeCount()).
Code codeAt(int i);

//! A status: a code, the stage it arose in, and a message for people.
struct Status {
  Code code = Code::Ok;
  Stage stage = Stage::Api;
  std::string message;

  bool ok() const { return code == Code::Ok; }
  static Status success() { return Status{}; }
};

//! The exception used inside the library. Public entry points catch it and return a Status
//! (or, in the bindings, turn it into a JS ConformeshError). Message: what went wrong and where.
class Error : public std::runtime_error {
 public:
  Error(Code code, Stage stage, const std::string& message)
      : std::runtime_error(message), code_(code), stage_(stage) {}
  Code code() const { return code_; }
  Stage stage() const { return stage_; }
  Status status() const { return Status{code_, stage_, what()}; }

 private:
  Code code_;
  Stage stage_;
};

//! Throw an Error (convenience; never returns).
[[noreturn]] void fail(Code code, Stage stage, const std::string& message);

}  // namespace conformesh
