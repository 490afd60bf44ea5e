// conformesh — sink cuts: a patch whose conformal scale factor collapses towards a point (a
// finger tip, an ear, a horn: curvature gathered in a small region) is cut in two by a path of
// input edges through that point, from its border to its border; and a patch whose border has a
// wedge too wide to lay out flat is cut through that corner.
//
// With u = 0 on the border (the free boundary condition, the least area distortion: Sawhney and
// Crane, Boundary first flattening, ACM TOG 2017) the scale cannot sink where the border passes:
// the point, on the border of both halves, keeps the scale of the border. The path leaves the
// point in two roughly opposite directions, so each half sees the point as a smooth stretch of
// its border (about half the 3D angle around it) and its map stays regular there. A slit ending
// at the point would not do: its end is a corner of the flat domain whose angle is set by the
// flow, not by the surface, and the map is singular there unless the two agree. A geodesic
// Voronoi split (splitPatch) leaves the point inside one part, which keeps most of the sink;
// cutting through it bounds the scale with one split per sink, so far fewer patches.
#pragma once

#include <cstdint>
#include <vector>

#include "features/edge_graph.h"
#include "features/segmentation.h"

namespace conformesh::features {

//! Cut patch p in two along two shortest paths of input edges inside it from `sink` (a vertex of
//! the patch on no curve) to its border, leaving the sink in roughly opposite directions (the
//! second turns at least 3/8 of the 3D angle around the sink away from the first, and each side
//! keeps at least `minWedge` radians). The edges become Cut edges; the junction repairs of a
//! split follow (repairNewCuts, over the patch only; none that takes the cut off the sink). False,
//! with the segmentation as it was, when there is no such pair of paths or the patch would not
//! end up as two or more disks, or the segmentation with no more patches than before; also false
//! when the sink is nearer the border than `minDepth` (along the first path). `others`: further sinks
//! of p (vertices on no curve); the second path may pass through them on its way to the border,
//! each time to the nearest one left when it is nearer than the border and leaving it as the
//! sink is left (3/8 of its angle sum from where the path came), at most 8 of them: one cut then
//! puts them all on the border (docs/decisions/0046); when that cut fails, the sink alone is cut.
//! In a patch with inner curves a path may end on one of them (then often parting nothing).
//! O(patch) per sink passed plus the rebuilds of the curves.
bool cutThroughSink(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t sink, double minWedge, double minDepth = 0,
                    const std::vector<uint32_t>& others = {});

//! cutThroughSink for the tip of a spike (an interior vertex whose angle sum is far below 2π: a
//! horn, a claw): the second path leaves the tip through the neighbour most opposite the first
//! that leaves each side `minWedge` (a spike tip's ring has few faces, often none 3/8 of the
//! way round). The tip is then on the border of both halves, where the free boundary keeps the
//! scale of the surface: no flat map squeezes the spike into a point inside a patch. In a patch
//! with inner curves, when the paths end on them and part nothing, the tip is cut again with
//! paths that keep off the inner curves and end on the border.
bool cutThroughSpike(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t tip, double minWedge);

//! Cut patch p in two along the shortest path of input edges inside it from `corner` (a vertex
//! on its border) to its border again, leaving the corner near the middle of p's wedge there
//! (each side at least 3/8 of the wedge and `minWedge` radians). For a wedge too wide to lay
//! out flat: a border vertex whose 3D angle inside the patch nears or passes 2π (a saddle of a
//! scan beside a curve) makes the free boundary's layout overlap itself however small the
//! patch around it, so a split that leaves it whole fails again. False, with the segmentation as
//! it was, as cutThroughSink. O(patch) plus the rebuilds of the curves.
bool cutThroughWideCorner(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t corner, double minWedge);

}  // namespace conformesh::features
