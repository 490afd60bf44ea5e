// conformesh — the last repair of the remesh: triangles still below the angle bound after the
// 3D angle certificate, where no planar refinement helps.
//
// What is left there is a small corner that a patch's boundary forces: a cut (ours, not a
// feature) meeting a feature curve or another cut at a small angle, with every patch on the
// narrow side. In the plane such a corner is an input angle between two segments, so the
// refinement keeps it; on the surface nothing forces it, because the cut is not a feature: the
// output must only be smooth across it. The repair moves the free vertices of such triangles
// (interior vertices and samples of cuts; never samples of feature or boundary curves, nor
// corners) over the input surface, in 3D: candidate positions are projected to the closest
// point of the input, and a move is kept only when the star's smallest 3D angle gets larger, no
// star triangle turns by more than kMaxNormalTurnDeg, no star triangle falls below the bound, the point lands in a patch the star already
// covers (a move never crosses a feature), and the star does not get farther from the input.
// When no vertex of those triangles can move any more, their free neighbours make room: a
// neighbour moves where the squared deficit of its star's angles below 40° falls, its star's
// smallest angle staying at or above the bound (a cut vertex boxed in between a feature and a
// neighbour whose own triangles are fine; camelhead). When they cannot either, a vertex of such a
// triangle may raise its star's smallest angle at the price of one more star triangle below the
// bound; a repair that ends with more triangles below the bound than it began with is undone.
// A moved vertex keeps its planar coordinates in RemeshResult::patches (they are for display
// and UVs): there it sits where the refinement put it, a short step from its surface position.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::repair {

struct RepairStats {
  size_t moves = 0;   //!< accepted vertex moves (0 when the repair was undone)
  int rounds = 0;     //!< passes over the triangles below the bound
  size_t left = 0;    //!< triangles still below the bound (and not exempt) at the end
};

//! `out`: the stitched output (positions change); `vertexFace`: per output vertex its input face
//! (updated for moved vertices); `triPatch`: patch per output triangle; `pinned`: per output
//! vertex, 1 when it must not move; `surface`: the input surface whose faces `vertexFace` names,
//! `surfacePatch` the patch of each of its faces; `isBad(t)`: output triangle t is below the bound
//! and not exempt. A move must raise the star's smallest angle and must not add a star triangle
//! below `boundDeg`. At most `maxRounds` passes (a hard cap); a pass that moves nothing ends it.
//! `deviationFloor`: a star may always get this far from the input (absolute; a small fraction
//! of the chord tolerance), besides as far as it was or 5 % of its shortest edge.
RepairStats relaxBelowBound(MeshBuffers& out, std::vector<uint32_t>& vertexFace, const std::vector<uint32_t>& triPatch,
                            const std::vector<uint8_t>& pinned, const MeshBuffers& surface,
                            const std::vector<uint32_t>& surfacePatch, const std::function<bool(size_t)>& isBad,
                            double boundDeg, int maxRounds, double deviationFloor = 0);

}  // namespace conformesh::repair
