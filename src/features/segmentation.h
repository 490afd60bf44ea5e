// conformesh — segmentation: feature curves, corners and patches that can each be flattened.
//
// Pipeline stage "segment" (docs/ARCHITECTURE.md): sharp edges by dihedral angle plus user feature
// edges and the open boundary form the feature curves; patches are the faces connected without
// crossing a curve; every patch is then cut until it is a topological disk (closed and
// genus > 0 patches, and patches with holes, whose flat metric has translational holonomy and
// cannot be laid out as one planar domain). Cuts are smooth: they are not features.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "features/edge_graph.h"
#include "features/patch_mesh.h"

namespace conformesh::features {

struct FeatureOptions {
  //! An interior edge is sharp when the angle between its two face normals exceeds this (degrees).
  double featureAngleDeg = 40.0;
  //! A vertex inside a curve becomes a corner when the polyline turns by more than this (degrees).
  double cornerTurnDeg = 50.0;
  //! Chains of sharp edges shorter than this (absolute) are features only where they stand out
  //! of their neighbourhood strongly or bridge two curves (features/creases.h): the facets of a
  //! coarse or noisy tessellation are not creases. 0 keeps every sharp edge. User feature edges
  //! are never dropped.
  double minFeatureLength = 0.0;
  //! The output's angle bound (degrees): two sharp edges of one face meeting below it (and below
  //! kSliverTipDeg) are no crease when the face is an outlier (features/creases.h), lest noise
  //! make exempt corners.
  double angleBoundDeg = 30.0;
  //! false: no edge is sharp by its dihedral angle; the features are featureEdges alone (the
  //! creases were detected on the mesh this one was refined from).
  bool detectCreases = true;
  //! Patches narrower than this (absolute; twice their area over their perimeter: the width of a
  //! strip) are merged into a neighbour by dropping the sharp edges between them: a chamfer or
  //! fillet strip far narrower than the output edges, a sliver face between two sharp edges.
  //! The remesh passes half the smallest edge length its sizing allows. 0 keeps every patch.
  double minPatchWidth = 0.0;
  //! User feature edges as vertex pairs (need not be sharp). A pair that is not an edge is an
  //! InvalidArgument error.
  std::vector<std::array<uint32_t, 2>> featureEdges;
  //! Hard cap on the number of patches cutting may create (IterationLimit when hit).
  uint32_t maxPatches = 4096;
  //! Length scale (absolute) at which the angles where a cut meets another curve are judged and
  //! improved (see improveCutJunctions), and the width below which a patch joins a neighbour
  //! across the cuts between them (features/merge_cut_patches.h); about the output edge length.
  //! 0 leaves cuts as found.
  double junctionScale = 0.0;
  //! A crease that ends inside a region (a dangling chain) stays a polyline inside its patch
  //! (Segmentation::isInnerCurve) instead of being continued until it closes the region off.
  bool innerCreases = false;
};

enum class EdgeKind : uint8_t { None = 0, Feature = 1, Boundary = 2, Cut = 3 };

//! A curve: a polyline of input edges between two corners (corners may coincide for a closed
//! loop through one corner).
struct Curve {
  EdgeKind kind = EdgeKind::Feature;
  std::vector<uint32_t> vertices;  //!< input vertices, vertices.size() == edges.size() + 1
  std::vector<uint32_t> edges;     //!< edges[i] joins vertices[i] and vertices[i+1]
  std::array<uint32_t, 2> patches{kNone, kNone};  //!< patches on the two sides (kNone: none)
  double length = 0;  //!< 3D arc length
  uint64_t order = 0;  //!< the order rebuildCurves traces it in (its ids follow it)
};

struct Segmentation {
  std::vector<EdgeKind> edgeKind;     //!< per input edge
  std::vector<uint32_t> edgeCurve;    //!< per input edge: curve id or kNone
  std::vector<uint8_t> vertexCorner;  //!< 0: not a corner, 1: corner, 2: artificial (closed loop)
  std::vector<Curve> curves;
  std::vector<uint32_t> facePatch;              //!< per input face
  std::vector<std::vector<uint32_t>> patches;   //!< faces of each patch (each a disk)
  //! The edge kinds the curves and patches were built from (empty: not built by rebuildCurves),
  //! so that a rebuild redoes only what changed since.
  std::vector<EdgeKind> builtKind;
  uint32_t sharpEdgeCount = 0;  //!< feature edges from the dihedral angle or the user
  uint32_t cutEdgeCount = 0;
  double cornerTurnDeg = 50.0;  //!< the option used, kept for rebuildCurves after splits
  double junctionScale = 0.0;  //!< the option used, kept for splitPatch
  double angleBoundDeg = 30.0;  //!< the option used, kept for splitPatch
  bool innerCreases = false;    //!< the option used: feature curves may lie inside a patch
  uint32_t reroutedCutEnds = 0;  //!< cut ends moved by improveCutJunctions
  uint32_t droppedFeatureEdges = 0;  //!< sharp edges dropped: short chains, borders of narrow patches
  uint32_t mergedNarrowPatches = 0;  //!< patches narrower than minPatchWidth merged into a neighbour

  bool isCurveEdge(uint32_t e) const { return edgeKind[e] != EdgeKind::None; }
  //! A feature curve with the same patch on both sides (FeatureOptions::innerCreases): the patch
  //! is not cut open along it, and its planar domain keeps it as a constrained polyline.
  bool isInnerCurve(uint32_t c) const {
    const Curve& cu = curves[c];
    return innerCreases && cu.kind == EdgeKind::Feature && cu.patches[0] == cu.patches[1] && cu.patches[0] != kNone;
  }
  //! Input edge e lies on an inner curve.
  bool isInnerEdge(uint32_t e) const { return edgeCurve[e] != kNone && isInnerCurve(edgeCurve[e]); }
  //! Per input edge: a patch is cut open along it (a curve edge, but for inner curves' edges).
  std::vector<uint8_t> curveMask() const;
};

//! Segment the mesh. Throws Error(InvalidArgument) for bad options, Error(IterationLimit) when
//! cutting needs more than maxPatches patches, Error(Cancelled) when progress returns false.
Segmentation segment(const EdgeGraph& g, const FeatureOptions& options, const ProgressFn& progress = {});

//! Split patch `p` into at least two disks by a geodesic Voronoi partition (k farthest-point
//! seeds, multi-source Dijkstra on the face graph) and rebuild curves, corners and patch ids.
//! Used when a patch's conformal scale factor varies too much. `seeds` (input faces of p, two or
//! more; else ignored): when the farthest points' partition leaves two of them in one part, the
//! seeds are the first seeds instead (the farthest points after them), so the cells keep them
//! apart. The junction repairs after the cuts keep at least half of what the cuts parted off the
//! largest part (docs/decisions/0047). Returns false when the patch is too small to split (fewer
//! than 2 faces).
bool splitPatch(const EdgeGraph& g, Segmentation& seg, uint32_t p, uint32_t parts = 2, const std::vector<uint32_t>& seeds = {});

//! The curve edges at input vertex v.
uint32_t curveValence(const EdgeGraph& g, const Segmentation& seg, uint32_t v);

//! After new cuts in `region` (a patch's faces that the cuts, already rebuilt into curves and
//! patches, part into two or more): their junctions improved and their ears, slivers and narrow
//! wedges repaired, as segment() does, within region. A repair must not undo the split: one that
//! leaves the region in one patch, or more than half of what the cuts parted off the largest
//! part back in it, or takes the cut off vertex `through` (the vertex a cut through a sink or a
//! corner is for; kNone: none) is undone and the next one tried (docs/decisions/0047).
void repairNewCuts(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& region, uint32_t through = kNone);

//! Per input vertex: the smallest wedge (radians) between the input's own feature and boundary
//! edges around it, the sum of the face angles between two consecutive such edges (cuts do not
//! count: they are not features). 2π for a vertex no feature touches, the full angle sum for one
//! on a single dangling feature edge. A vertex whose smallest wedge is below the angle bound is an
//! input corner that no mesh of the surface can give better angles: the remesh exempts it.
std::vector<double> featureWedgeAngles(const EdgeGraph& g, const Segmentation& seg);

//! Continue every dangling feature curve (a vertex with exactly one curve edge; `from`: only
//! those ending at these vertices) along the straightest path of input edges until it meets a
//! curve, so no patch contains a slit. A step onto another curve's dangling end that would make a
//! wedge below 45° there is taken only when no other step is left. Marks the new edges Cut; the
//! caller rebuilds the curves.
void extendDanglingCurves(const EdgeGraph& g, Segmentation& seg, const std::vector<uint32_t>& from = {});

//! Patch p's inner curves (Segmentation::isInnerCurve) continued from their dangling ends as
//! extendDanglingCurves does, the parts that closes off cut into disks, curves and patches
//! rebuilt: what segment() without innerCreases makes of the patch, for a patch whose flattening
//! fails or spreads its scale too far with them inside. False (nothing changed) when it has none.
bool closeInnerCreases(const EdgeGraph& g, Segmentation& seg, uint32_t p);

//! Recompute curves, corners and patches from seg.edgeKind (after edges were marked). Only the
//! curves and patches beside the edges changed since the last rebuild are redone; the result,
//! ids included, is the same as a rebuild from scratch (features/rebuild_curves.cpp).
void rebuildCurves(const EdgeGraph& g, Segmentation& seg);

//! Patches only: the faces connected across edges that are not curve edges (seg.facePatch,
//! seg.patches, numbered by their smallest face); the curves are left as they are.
void floodPatches(const EdgeGraph& g, Segmentation& seg);

}  // namespace conformesh::features
