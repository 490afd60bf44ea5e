// conformesh — remesh stage 2: every patch flattened (conformal/flatten.h), with its planar/3D
// scale and target size per vertex. A patch whose flattening fails or distorts too much is split
// (features/segmentation.h splitPatch) and its parts flattened instead.
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! One PatchWork per patch of surf.seg, in its order. Changes surf.seg by the splits (their count goes
//! to rep.patchSplitsForScale, a warning per fallback to rep.warnings). Fails with
//! NumericalFailure when a patch too small to split cannot be flattened, IterationLimit when the
//! splits do not settle within the segmentation's patch cap.
Patches flattenPatches(Surface& surf, const RemeshOptions& opt, const Progress& progress, RemeshReport& rep);

}  // namespace conformesh::pipeline
