// conformesh — the pipeline stages: the one ordered list.
//
// remesh() runs the stages of CONFORMESH_REMESH_STAGES in this order (src/remesh/remesh.cpp).
// The enum, the names in errors and progress reports, the report's seconds per stage
// (RemeshReport::seconds), the CLI's report, the WASM module's stageTable() and overall progress
// all come from this table; the TypeScript table (bindings/src/stages.ts) is checked against the
// module's export by tests/js/stages.test.ts.
#pragma once

namespace conformesh {

// X(enum name, seconds key, name in reports, label for users, progress weight)
//
// The weight is the stage's typical share (percent) of a remesh's run time, the interval of the
// call's overall progress (progressInterval) its own progress sweeps. Lift reports no progress of
// its own: it runs per patch inside refine, whose events cover it. The rounds after the first
// re-mesh what the certificate asked for and report as certificate; their time still goes to
// the stage that spends it. Precondition reports no progress either: it runs between the two
// segmentations of prepare (remesh/prepare.cpp), whose events cover it.
#define CONFORMESH_REMESH_STAGES(X)                                 \
  X(Validate, validate, "validate", "check input", 1)               \
  X(Precondition, precondition, "precondition", "precondition", 0)  \
  X(Segment, segment, "segment", "segment", 25)                     \
  X(Flatten, flatten, "flatten", "flatten", 30)                     \
  X(CurveMesh, curveMesh, "curve-mesh", "curves", 1)                \
  X(Refine, refine, "refine", "refine", 20)                         \
  X(Lift, lift, "lift", "lift to 3D", 0)                            \
  X(Optimize, optimize, "optimize", "optimize", 8)                  \
  X(Stitch, stitch, "stitch", "stitch", 1)                          \
  X(Certificate, certificate, "certificate", "angle check", 5)      \
  X(Repair, repair, "repair", "repair", 1)                          \
  X(Report, report, "report", "report", 8)

// Every stage an error or a progress report can name: reading a file, remesh()'s stages in their
// order, writing a file, and the entry points' own checks.
#define CONFORMESH_STAGE_TABLE(X)      \
  X(Read, read, "read", "read", 0)     \
  CONFORMESH_REMESH_STAGES(X)          \
  X(Write, write, "write", "write", 0) \
  X(Api, api, "api", "call", 0)

enum class Stage : int {
#define CONFORMESH_X(id, key, name, label, weight) id,
  CONFORMESH_STAGE_TABLE(CONFORMESH_X)
#undef CONFORMESH_X
};

//! remesh()'s stages in the order it runs them.
inline constexpr Stage kRemeshStages[] = {
#define CONFORMESH_X(id, key, name, label, weight) Stage::id,
    CONFORMESH_REMESH_STAGES(CONFORMESH_X)
#undef CONFORMESH_X
};

//! Number of rows in the stage table; a Stage's value is its row.
int stageCount();
//! Whether remesh() runs stage s (a row of CONFORMESH_REMESH_STAGES): its seconds are in the report.
bool isRemeshStage(Stage s);
//! Stage name as used in reports and JSON ("curve-mesh"); "unknown" for values not in the table.
const char* stageName(Stage s);
//! The key of the stage's seconds in the report ("curveMesh").
const char* stageKey(Stage s);
//! The stage's name for people ("curves"), as the CLI and the demo page show it.
const char* stageLabel(Stage s);
//! The stage's progress weight (percent of a typical remesh); 0 outside remesh().
int stageWeight(Stage s);

//! The interval [lo, hi] of a remesh's overall progress (0 to 1) over which stage s's own
//! progress runs: the weights of the stages before it, and with it, over all the weights.
struct StageInterval {
  double lo = 0, hi = 0;
};
StageInterval progressInterval(Stage s);

}  // namespace conformesh
