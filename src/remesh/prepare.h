// conformesh — remesh stage 1: the surface model. The validated input is preconditioned,
// segmented into feature curves and disk patches, and sized; nothing after this stage reads the
// options' size fields again.
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! InvalidArgument (stage Api) for an option out of its range (remesh.h documents each).
void checkOptions(const RemeshOptions& opt);

//! Segment and size a validated input (`input`: the caller's buffers, for per-vertex options).
//! Fills the report's estimate and target; fails with TooLarge when the estimate is over the
//! limits (remesh/limits.h), InvalidArgument for feature edges or a sizing out of range. The
//! precondition's time goes to its own stage on `clock`, the rest to the current one.
Surface prepareSurface(ValidatedMesh vm, const MeshBuffers& input, const RemeshOptions& opt, const Progress& progress,
                       RemeshReport& rep, StageClock& clock);

}  // namespace conformesh::pipeline
