// conformesh — the remesh pipeline: a triangle mesh in, a new high-quality triangulation of the
// same surface out. Its stages, in order, are CONFORMESH_REMESH_STAGES (core/stages.h); what
// each does and hands on is in docs/ARCHITECTURE.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "conformal/ricci_flow.h"
#include "core/mesh_buffers.h"
#include "core/status.h"

namespace conformesh {

struct RemeshOptions {
  //! Angle bound (degrees) for every output triangle, measured in 3D, except at exempt corners
  //! (input corners whose own angle is below it; see ExemptCorner). Range [0, 34].
  double minAngleDeg = 30.0;
  //! Target edge length: the mean output edge length in flat regions. Absolute when > 0, else
  //! targetEdgeLengthRel times the bounding-box diagonal.
  double targetEdgeLength = 0.0;
  double targetEdgeLengthRel = 0.01;
  //! Curvature adaptation: chord deviation bound (absolute when >= 0, else chordToleranceRel ·
  //! diagonal; 0 switches curvature sizing off).
  double chordTolerance = -1.0;
  double chordToleranceRel = 1e-3;
  //! Error-driven remeshing: the largest two-sided Hausdorff distance allowed between the output
  //! and the input (absolute when > 0, else maxErrorRel · diagonal when > 0; both 0, the default:
  //! off). When on, the sizes grow as large as the chord error, the curvature and the angle bound
  //! allow (the target edge length still sets the scale of the cuts and the smallest edge),
  //! chordTolerance is chosen by remesh, minFeatureLength's default is 0 (every sharp edge is
  //! kept: spanning a crease costs its height), and the output's measured Hausdorff distance is
  //! at most this, else IterationLimit (remesh/max_error.h).
  double maxError = 0.0;
  double maxErrorRel = 0.0;
  //! Neighbouring edge length ratio bound (> 1).
  double gradation = 1.5;
  //! Edge length clamps (absolute; < 0: target/10 and target).
  double minEdgeLength = -1.0;
  double maxEdgeLength = -1.0;
  //! Optional per-input-vertex target edge length (absolute), one per input vertex.
  std::vector<double> vertexSizing;
  //! Sharp edges: dihedral angle above this (degrees) are features.
  double featureAngleDeg = 40.0;
  //! A feature curve turning by more than this at a vertex gets a corner there (degrees).
  double cornerTurnDeg = 50.0;
  //! Sharp edges are creases only in chains (straight continuations) that stand out of their
  //! neighbourhood and are at least this long, or that stand out strongly or bridge two curves
  //! (features/creases.h): the facets of a coarse or noisy surface are not creases (absolute;
  //! < 0: twice the target edge length, 0 when error-driven; 0: keep every sharp edge). User
  //! feature edges are always kept. The report counts the dropped edges.
  double minFeatureLength = -1.0;
  //! Patches narrower than this (twice their area over their perimeter) are merged into a
  //! neighbour by dropping the sharp edges between them; the strip's other border keeps the
  //! feature, within this width (absolute; < 0: half the smallest edge length the sizing allows,
  //! target/20 by default; 0, the default: keep every patch, so every sharp edge). A strip far
  //! narrower than the output edges (a CAD chamfer) is otherwise meshed below the sizing's floor,
  //! with a graded band around it (docs/decisions/0007-narrow-strips.md).
  double minPatchWidth = 0.0;
  //! User feature edges (input vertex pairs).
  std::vector<std::array<uint32_t, 2>> featureEdges;
  //! The boundary condition each patch's flattening tries first; when its layout fails (overlaps
  //! itself, or loses precision) the others follow, in the order Free, Corners, Circle. Free
  //! (default): u = 0 on the boundary, isometric on developable patches (planar angles are 3D
  //! angles). Corners: corners keep their 3D angle, the sides bend. Circle: a round disk.
  conformal::BoundaryCondition boundary = conformal::BoundaryCondition::Free;
  //! A patch whose conformal scale factor ratio max/min e^u exceeds this is split in two (the
  //! planar sizing would otherwise span a huge range and the flow's layout lose precision).
  double maxScaleRatio = 50.0;
  //! Cap on the rounds of the 3D angle certificate (re-meshing patches with smaller planar size
  //! where a lifted triangle is below the bound). The rounds also stop after two in a row that
  //! do not beat the best one; the best round is the output. A stitch defect (non-manifold)
  //! left at the cap gets two more rounds in which its patches keep their boundary.
  int maxCertificateRounds = 6;
  //! Optimize every patch's mesh after refinement (issue 9): ODT vertex moves and flips in the
  //! conformal plane, accepted only when the lifted 3D triangles get better and the angle bound
  //! holds (remesh/optimize.h). Raises the mean per-triangle min angle; never lowers the worst.
  bool optimize = true;
  int optimizeIterations = 2;       //!< passes (hard cap), >= 0; each costs ~5 µs per output vertex
  double optimizeTolerance = 1e-3;  //!< stop when a pass gains less than this fraction of the mean min angle
  //! Return every patch's planar data in RemeshResult::patches (for display: the flattened
  //! input and the refined planar mesh) and the patch of every output triangle.
  bool returnPatches = false;
  //! Carry the input's uvs and attributes (MeshBuffers::uvs, ::attributes: texture coordinates,
  //! normals, colours, any value) over to the output (remesh/carry_attributes.h): the edges where
  //! a per-corner attribute jumps (uv seams: attributeSeams, mesh/mesh_attributes.h) are kept as
  //! feature curves, like featureEdges, so no output triangle straddles one and texture charts
  //! stay whole; every output corner's value is the input's interpolated at its pull-back point
  //! (RemeshResult::cornerInputFace, on the triangle's side of the seams). A per-vertex input
  //! attribute stays per vertex, a per-corner one per corner. Normals are renormalized. false:
  //! the output has positions and triangles only, as without attributes.
  bool carryAttributes = true;
  //! Return RemeshResult::cornerInputFace and cornerBarycentric even for an input without
  //! attributes (with attributes and carryAttributes they always come back).
  bool returnSurfacePoints = false;
  //! Two-sided Hausdorff distance in the report (sampled; costs time on big meshes).
  bool computeHausdorff = true;
  size_t hausdorffSamples = 50000;
  //! Threads over the patches (flattening, refinement, lift, optimization) and over the report's
  //! distances to the input (core/parallel_for.h): 0 (default) the hardware's concurrency, 1 serial,
  //! at most 1024. The output and the report but its seconds are the same for every count. Always
  //! 1 in the WebAssembly build.
  int threads = 0;
  //! Output limits (remesh/limits.h). Before flattening and refinement, the output size and the
  //! peak memory are predicted from the sizing field; after refinement the real counts are
  //! checked. Exceeding a limit fails with TooLarge (message: the estimate or count, and the
  //! limit). 0 is InvalidArgument, NOT "no limit": pass a huge value (SIZE_MAX, 1e300) to lift one.
  //! Defaults: 16 M vertices and 32 M triangles (as many as validate() accepts as input, 32-bit
  //! indices throughout), and 3 GiB of heap: a WASM module has at most 4 GiB, and this keeps room
  //! for the input, the JS copies of the result and the runtime.
  size_t maxVertices = size_t(16) << 20;
  size_t maxTriangles = size_t(32) << 20;
  double maxMemoryBytes = 3.0 * double(size_t(1) << 30);
  //! The output must have the input's components, boundary loops and Euler characteristic, and no
  //! non-manifold edge or vertex; otherwise remesh fails with InternalError (stage Report; the
  //! message says what differs) and an empty mesh. true (default false): the mesh, report and
  //! patches come back along with that status, to inspect the defect.
  bool keepDefectiveOutput = false;
  //! For testing the check above: break the stitched output (a flipped copy of its first triangle
  //! on a new vertex, so one edge has three triangles) so that the check fails. Default false.
  bool forceTopologyDefect = false;
};

//! An input corner where the input's own feature or boundary curves make a wedge below the bound
//! (features::featureWedgeAngles). Its triangles are listed and exempt from the bound: those
//! touching it, and those with an edge across its small wedge (both ends on two different curves
//! meeting at the corner, seen from it under less than the bound: the skinny triangles Ruppert's
//! concentric shells leave there, forced by the input; Shewchuk 2002).
struct ExemptCorner {
  uint32_t inputVertex = 0;
  uint32_t outputVertex = 0;
  double angleDeg = 0.0;
  std::vector<uint32_t> triangles;  //!< output triangles exempt for it: touching it or across its wedge (above)
};

//! Wall seconds per stage of remesh(), one field per row of CONFORMESH_REMESH_STAGES
//! (core/stages.h), and the whole call; the stages sum to it. Refine and lift run side by side
//! on the threads: their section's wall time is split in proportion to their thread-seconds.
struct StageSeconds {
#define CONFORMESH_X(id, key, name, label, weight) double key = 0;
  CONFORMESH_REMESH_STAGES(CONFORMESH_X)
#undef CONFORMESH_X
  double total = 0;

  //! The field of stage s; nullptr for a stage remesh() does not run (read, write, api).
  double* of(Stage s) {
    switch (s) {
#define CONFORMESH_X(id, key, name, label, weight) \
  case Stage::id:                                  \
    return &key;
      CONFORMESH_REMESH_STAGES(CONFORMESH_X)
#undef CONFORMESH_X
      default:
        return nullptr;
    }
  }
  const double* of(Stage s) const { return const_cast<StageSeconds*>(this)->of(s); }
};

struct RemeshReport {
  size_t inputTriangles = 0, inputVertices = 0;
  size_t triangles = 0, vertices = 0;
  double minAngle = 0, maxAngle = 0, meanMinAngle = 0;  //!< degrees, all triangles
  double pctBelow20 = 0, pctBelow26 = 0, pctBelow30 = 0;
  double pctMinAtLeast40 = 0, pctMinAtLeast50 = 0;  //!< % of triangles whose min angle is >= 40°, >= 50°
  size_t optimizeMoves = 0, optimizeFlips = 0;       //!< accepted by the optimization (moves include curve-sample slides)
  size_t repairMoves = 0;  //!< free vertices moved over the surface where the certificate left a triangle below the bound (remesh/repair.h)
  double minAngleOutsideExempt = 0;  //!< smallest angle over triangles no exempt corner lists
  size_t trianglesBelowBoundOutsideExempt = 0;
  std::vector<ExemptCorner> exemptCorners;
  double meanEdgeLength = 0;
  double targetEdgeLength = 0;
  double delaunayFraction = 0;  //!< interior edges that are Delaunay in 3D
  double hausdorffRel = -1;     //!< two-sided, relative to the input bbox diagonal (-1: not computed)
  double maxDistanceToInputRel = 0;  //!< largest output vertex distance to the input / diagonal
  size_t featureCurves = 0, featureCurvesKept = 0;
  size_t sharpEdges = 0, cutEdges = 0;
  size_t droppedFeatureEdges = 0;  //!< sharp edges found not to be creases (minFeatureLength)
  size_t seamEdges = 0;  //!< input edges kept as feature curves for being attribute seams (carryAttributes)
  size_t patches = 0, curves = 0, curveSamples = 0;
  std::vector<int> flowIterations;  //!< Newton iterations per patch
  size_t patchSplitsForScale = 0;
  int conformingRounds = 0, certificateRounds = 0;
  double estimatedTriangles = 0;  //!< output size predicted before refinement (remesh/limits.h)
  bool topologyPreserved = false;  //!< the topology check passed (false only with keepDefectiveOutput)
  StageSeconds seconds;
  std::vector<std::string> warnings;
};

//! One patch in the plane (RemeshOptions::returnPatches).
struct RemeshPatch {
  std::vector<double> layoutUv;            //!< 2 per vertex: the flattened input patch
  std::vector<uint32_t> layoutTriangles;   //!< its triangles (the input faces of the patch)
  std::vector<uint32_t> layoutInputFace;   //!< per layout triangle: its triangle in the input mesh
  std::vector<double> layoutFactor;        //!< per layout vertex: log scale factor u
  std::vector<double> uv;                  //!< 2 per vertex: the refined (and optimized) planar mesh
  std::vector<uint32_t> triangles;         //!< its triangles, in the order of the output triangles of the patch
  std::vector<uint32_t> outputVertex;      //!< per planar vertex: the output vertex it became
};

struct RemeshResult {
  Status status;  //!< Ok, or the failure (mesh then empty, but with keepDefectiveOutput after a failed topology check)
  MeshBuffers mesh;
  RemeshReport report;
  std::vector<RemeshPatch> patches;        //!< with RemeshOptions::returnPatches
  std::vector<uint32_t> patchOfTriangle;   //!< with RemeshOptions::returnPatches: patch per output triangle
  //! The pull-back point of every output corner (corner c of triangle t is 3·t + c), with
  //! attributes carried or RemeshOptions::returnSurfacePoints: the input triangle (input
  //! numbering) its vertex lies on, on the triangle's side of every attribute seam, and
  //! 3 barycentric coordinates per corner (w.r.t. that input triangle's corners 0, 1, 2; they sum
  //! to 1, and weight its vertices to the output vertex's position up to rounding). Empty otherwise.
  std::vector<uint32_t> cornerInputFace;
  std::vector<double> cornerBarycentric;
};

//! Remesh a triangle mesh. Never throws: failures come back in `status` (codes from the input
//! validation, InvalidArgument for bad options, IterationLimit when a cap is hit, Cancelled,
//! NumericalFailure from the flattening, InternalError when the output's topology differs from
//! the input's: see RemeshOptions::keepDefectiveOutput). Progress goes through every stage;
//! returning false cancels.
RemeshResult remesh(const MeshBuffers& input, const RemeshOptions& options = {}, ProgressFn progress = {});

}  // namespace conformesh
