// conformesh — error-driven remeshing: the two-sided Hausdorff distance to the input is the
// constraint (RemeshOptions::maxError), not the edge length. The setting of Hu, Yan, Bommes,
// Alliez and Benes, "Error-bounded and feature preserving surface remeshing with minimal angle
// improvement" (IEEE TVCG 2017), reached here by the curvature sizing's chord tolerance: the
// whole remesh runs with a tolerance below the bound, and its measured Hausdorff distance decides
// the next attempt, a few at most: above the bound, the sizes are cut where the distance was
// exceeded (RemeshOptions::vertexSizing, at the same tolerance), or the tolerance is tightened
// when no sample shows where or a cut did not lower the distance; far below it, the tolerance is
// loosened (a coarser mesh would do).
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
