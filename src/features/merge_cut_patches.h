// conformesh — segmentation step: narrow patches that only cuts border, joined to a neighbour.
#pragma once
#include <cstddef>
#include <cstdint>
#include "features/edge_graph.h"
#include "features/segmentation.h"
namespace conformesh::features {
//! Join each patch narrower than `maxWidth` (twice its area over its perimeter: the width of a
//! strip) to a neighbour across the cut edges between them, when their union is still a disk
//! (features/patch_mesh.h: one boundary loop, χ = 1, no pinch). Cuts are not features: such a
//! cut parts nothing the topology needs, and a strip narrower than an output edge holds no
//! interior vertex, so its border only forces smaller triangles on both sides of it. Cutting
//! into disks by geodesic Voronoi cells leaves such strips between the cells and the curves
//! (man: 38 regions cut into 65 patches, 20 of them under three target lengths squared).
//! Narrowest first, each into the neighbour it shares the most cut edges with that keeps the
//! union a disk; one pass, each patch tried once against its neighbours as they are by then.
//! The cut edges between joined patches become plain edges; the caller rebuilds the curves.
//! maxWidth <= 0 joins none. `region` (input faces; empty: all): only the patches over it join,
//! and only each other. `keep` (per edge; empty: none): cut edges no join makes plain, a
//! neighbour across one is not joined. `pairs`: each patch takes part in one join at most (each
//! joined patch is two of the patches as they were), and the joined patches hold at most
//! `maxFaces` faces together (a join that would pass it is skipped). Returns the number of
//! joins. O(Σ over the tries of the two patches' faces). docs/decisions/0041.
uint32_t mergeCutPatches(const EdgeGraph& g, Segmentation& seg, double maxWidth, const std::vector<uint32_t>& region = {},
                         const std::vector<uint8_t>& keep = {}, bool pairs = false, size_t maxFaces = SIZE_MAX);
}  // namespace conformesh::features
