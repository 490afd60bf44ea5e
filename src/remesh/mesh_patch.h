// conformesh — remesh stage 3, per patch: the Delaunay refinement of its boundary samples in its
// plane (planar/refine.h), the lift of every new vertex onto the input (conformal/overlay.h),
// and the optimization of the result judged in 3D (remesh/optimize.h).
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! Refine patch p from scratch with its spots and required points; a boundary split becomes a
//! curve sample the patches on that curve take up (curve_samples.h). splitSegments = false keeps
//! the boundary as it is; the lift's time goes to Stage::Lift on `clock`. Fails with the
//! refinement's status (IterationLimit at its cap), NumericalFailure when a vertex cannot be
//! lifted, InternalError for a boundary that is no polygon.
void meshPatch(const Surface& surf, const RemeshOptions& opt, Meshing& m, uint32_t p, StageClock& clock,
               bool splitSegments = true);

//! Optimize patch p's latest meshing in its plane, judged in 3D; `active` (empty: all) the
//! vertices that may move. Adds its moves and flips to rep.
void optimizeMesh(const Surface& surf, const RemeshOptions& opt, Meshing& m, uint32_t p, RemeshReport& rep,
                  const std::vector<uint8_t>& active = {});

}  // namespace conformesh::pipeline
