// conformesh — small patches merged across cuts: cutting patches into disks (geodesic Voronoi
// cells) and continuing dangling curves leave patches of a few output triangles between cuts;
// each costs a border of samples and the grading around it. A cut is ours, so one between such a
// patch and a neighbour can go when the two together are still a disk.
#pragma once

#include <cstdint>

#include "features/edge_graph.h"
#include "features/segmentation.h"

namespace conformesh::features {

//! Merge every patch of area below minArea into a neighbour across a cut curve between them
//! (the smaller patch first, then the longer curve), when the merged patch is a disk; repeated
//! while a merge is made. Features and boundaries are never removed. Rebuilds the curves.
//! Returns the number of merges.
uint32_t mergeSmallPatches(const EdgeGraph& g, Segmentation& seg, double minArea);

}  // namespace conformesh::features
