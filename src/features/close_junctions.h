// conformesh — close junctions merged: two curve corners joined by a curve far shorter than the
// output edges are a feature of that size the refinement must resolve and grade away from.
#pragma once

#include <cstdint>
#include <vector>

#include "features/segmentation.h"

namespace conformesh::features {

//! Corners joined by a curve shorter than this many junction scales (about the output edge
//! length) are merged where one is a junction of cuts: the minLength segment and splitPatch pass.
constexpr double kCloseJunctionFactor = 0.25;

//! Where a curve shorter than minLength joins two corners and one of them is a junction only of
//! cuts (ours, not features), move those cuts to end at the other corner: each cut's stretch
//! near the junction is replaced by the shortest path of input edges to the other corner (a cut
//! that was the short curve itself is dropped). Kept only when every patch it touches stays a
//! disk, no patch is merged or split, the new paths have no hairpin, and the smallest wedge at
//! the corner that takes the cuts is at least min(45°, the smallest before at either corner).
//! A junction of three cuts a hundredth of an output edge from another (Voronoi borders meeting
//! twice, a cut meeting a crease beside its corner) costs a refinement graded down to that
//! length: hundreds of triangles, where the merged junction costs none. `region` (input faces;
//! empty: all): only curves beside it are tried. Rebuilds the curves. Returns the merges.
uint32_t mergeCloseJunctions(const EdgeGraph& g, Segmentation& seg, double minLength,
                             const std::vector<uint32_t>& region = {});

}  // namespace conformesh::features
