// conformesh — cut repairs: where a cut (ours, not a feature) meets another curve or kinks at a
// small angle, the patch beside it would have a corner no mesh can fix; these move the cut.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "features/segmentation.h"

namespace conformesh::features {

//! Cuts are ours, so where one meets another curve at a small angle (a Voronoi border arriving
//! obliquely, three borders meeting at a point), the patch on the narrow side would have a small
//! corner that no mesh can fix. The angle is taken at about `scale` from the junction, or
//! between the first input edges where those meet at less than 45° (a cut crossing a sliver face
//! at a right angle on the whole can leave the curve there at a few degrees). Reroute such a cut
//! end: from the cut's vertex about 3·scale before the end, the shortest path of input edges to
//! a smooth point of another curve (a shortest path to a curve meets it at a right angle); kept
//! only when the angle gets better and every patch stays a disk. Rebuilds the curves. Returns the
//! number of ends rerouted. `region` (input faces; empty: all): only cuts beside it are rerouted
//! (splitPatch passes the split patch, so a split does not retry every cut end of the mesh).
uint32_t improveCutJunctions(const EdgeGraph& g, Segmentation& seg, double scale, const std::vector<uint32_t>& region = {});

//! Where a cut makes a wedge below 45° at a vertex (a kink in the cut, or a cut leaving another
//! curve at a small angle), move the cut across the wedge's faces: its edges at the vertex stop
//! being cuts and the far edges of the wedge's faces (the rim) become the cut. Kept when the
//! smallest wedge at the vertex and along the rim grows and neither end of the rim is left
//! narrower than 45° and than it was (an ear moved onto the end of a crease the cut continues
//! stays below the bound there: elk at 20°, 26°); every patch must stay a disk (else all
//! moves are undone). Cuts follow input edges, so at the scale of one input edge they can
//! zigzag: the patch there has a corner no mesh can give better angles, and the 3D certificate
//! cannot refine it away. Returns the number of moves. `region` (input faces; empty: all): only
//! wedges in it are tried (splitPatch passes the split patch, whose new cuts lie in it, so a
//! split costs the patch's size, not the mesh's). keepSplit: a move that would leave the faces of
//! `region` (not empty) in one patch (a pruned branch that separated its parts) is not made (splitPatch: the
//! parts are what the split is for); a sliver patch inside a wedge may go.
uint32_t straightenCutEars(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& region = {},
                           bool keepSplit = false);

//! A patch of at most four faces with a corner below minAngle (radians) where only cuts meet (a
//! sliver face cut all round, left by halving a small region: any mesh of it has the sliver's
//! angles) joins the patch across one of its cut borders, longest first: the cuts between the
//! two go, and the cut branches left dangling. Kept when every patch it touches stays a disk.
//! Returns the number of patches absorbed. `region` (input faces; empty: all): only its patches.
uint32_t absorbCutSlivers(const EdgeGraph& g, Segmentation& seg, double minAngle, const std::vector<uint32_t>& region = {});

//! A wedge narrower than minAngle (radians) at a vertex, between a cut and another curve, inside
//! a larger patch (two needles between cuts routed along a fan of them: no mesh of the wedge
//! keeps the bound, and refining towards it splits the cuts tens of times): its faces join the
//! patch across the cut, whose border then runs along the wedge's far edges. Kept when every
//! patch it touches stays a disk and no wedge at the vertices it changes gets narrower than the
//! narrower of minAngle and what it was. Returns the number of wedges moved. `region` (input
//! faces; empty: all): only the vertices of its faces.
uint32_t moveNarrowCutWedges(const EdgeGraph& g, Segmentation& seg, double minAngle, const std::vector<uint32_t>& region = {});

//! The number of patches the faces `faces` lie in.
size_t patchesOver(const Segmentation& seg, const std::vector<uint32_t>& faces);

//! The most of the faces `faces` that lie in one patch.
size_t largestShare(const Segmentation& seg, const std::vector<uint32_t>& faces);

}  // namespace conformesh::features
