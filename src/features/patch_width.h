// conformesh — how wide a patch is across from each of its boundary edges: the local feature
// size of a thin strip (a chamfer, a blade's rim) or of a corner sharper than 30°, where the
// refinement must place samples as close as the features are to keep its angle bound.
#pragma once

#include <array>
#include <vector>

#include "features/edge_graph.h"
#include "features/segmentation.h"

namespace conformesh::features {

//! Per input edge e and side s (the face edgeFaces[e][s]): the distance from e's midpoint to the
//! nearest boundary edge of the same patch that lies across from it, or +infinity where there is
//! none within maxDistance (and for edges inside a patch, and sides without a face). An inner
//! curve's edges (Segmentation::isInnerCurve) count as boundary edges on both sides, each side
//! measured to what lies on that side: the refinement samples them as it samples a border.
//! "Across": the segment joining the midpoint to its closest point on the other edge is within
//! 60° of the normal of both edges. The next edges along a smooth curve fail that test, and so
//! do the edges of another curve meeting e's curve at a corner wider than 30°; both sides of a
//! strip and of a sharper corner pass it. An edge is never across from itself. Distances are
//! straight 3D lines: exact across a flat strip, never longer than the way across on the
//! surface. O(E log E) over the patches' boundary edges.
std::vector<std::array<double, 2>> patchWidths(const EdgeGraph& g, const Segmentation& seg, double maxDistance);

//! Per patch of seg (by seg.facePatch): its area, and its perimeter, the length of its edges on
//! the boundary or beside another patch (an edge with the patch on both sides counts for
//! nothing). 2 · area / perimeter is the width of a strip. O(F + E).
struct PatchExtents {
  std::vector<double> area, perimeter;
};
PatchExtents patchExtents(const EdgeGraph& g, const Segmentation& seg);

}  // namespace conformesh::features
