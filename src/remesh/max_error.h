// conformesh — error-driven remeshing: the two-sided Hausdorff distance to the input is the
// constraint (RemeshOptions::maxError), not the edge length. The setting of Hu, Yan, Bommes,
// Alliez and Benes, "Error-bounded and feature preserving surface remeshing with minimal angle
// improvement" (IEEE TVCG 2017), reached here by the curvature sizing's chord tolerance: the
// whole remesh runs with a tolerance below the bound, its measured Hausdorff distance decides
// whether the tolerance is tightened (the distance was above the bound; first the cone tips'
// sizes alone, RemeshOptions::coneTips) or loosened (far below it: a coarser mesh would do), a
// few times at most.
#pragma once

#include <functional>

#include "remesh/remesh.h"

namespace conformesh {

//! Whether the options ask for error-driven remeshing (maxError or maxErrorRel > 0).
bool errorDriven(const RemeshOptions& options);

//! The bound in the input's units (checkOptions has rejected negative and non-finite values).
double maxErrorBound(const MeshBuffers& input, const RemeshOptions& options);

//! Run `attempt` (a whole remesh with the options given) with chord tolerances chosen so that the
//! report's Hausdorff distance is within the bound: the coarsest attempt within it wins. Fails
//! with IterationLimit when no attempt is within the bound; an attempt's own error is returned.
RemeshResult remeshWithinError(const MeshBuffers& input, const RemeshOptions& options,
                               const std::function<RemeshResult(const RemeshOptions&)>& attempt);

}  // namespace conformesh
