// conformesh — how wide a patch is across from each of its boundary edges: the local feature
// size of a thin strip (a chamfer, a blade's rim) or of a corner sharper than 60°, where the
// refinement must place samples as close as the features are to keep its angle bound.
#pragma once

#include <array>
#include <vector>

#include "features/edge_graph.h"
#include "features/segmentation.h"

namespace conformesh::features {

//! Per input edge e and side s (the face edgeFaces[e][s]): the distance from e's midpoint to the
//! nearest boundary edge of the same patch that lies across from it, or +infinity where there is
//! none within maxDistance (and for edges inside a patch, and sides without a face).
//! "Across": the segment joining the midpoint to its closest point on the other edge is within
//! 60° of the normal of both edges (their tangents make less than 60° with each other's plane
//! of crossing), so the next edges along a smooth curve and the other curve of a corner wider
//! than 60° are not counted, while both sides of a strip and of a sharp corner are. Edges that
//! share a vertex are never across. Distances are 3D, along straight lines: right across a
//! strip, an overestimate of nothing. O(E log E) over the patches' boundary edges.
std::vector<std::array<double, 2>> patchWidths(const EdgeGraph& g, const Segmentation& seg, double maxDistance);

}  // namespace conformesh::features
