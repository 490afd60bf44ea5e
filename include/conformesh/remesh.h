// conformesh — the remesh pipeline: a triangle mesh in, a new high-quality triangulation of the
// same surface out. Its stages, in order, are CONFORMESH_REMESH_STAGES (conformesh/stages.h); what
// each does and hands on is in docs/ARCHITECTURE.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "conformesh/buffers.h"
#include "conformesh/status.h"
#include "conformesh/remesh_schema.h"

namespace conformesh {

//! remesh()'s options: one field per row of CONFORMESH_REMESH_OPTIONS (conformesh/remesh_schema.h), with its
//! default, and the per-element inputs.
struct RemeshOptions {
#define CONFORMESH_X(type, name, fallback, lo, hi, flag, value, help) type name = fallback;
  CONFORMESH_REMESH_OPTIONS(CONFORMESH_X)
#undef CONFORMESH_X
  //! Optional per-input-vertex target edge length (absolute), one per input vertex. Error-driven
  //! (maxError) without minEdgeLength, honoured below the default minimum: the search cuts the
  //! sizes through it where an attempt was too far from the input.
  std::vector<double> vertexSizing;
  //! User feature edges (input vertex pairs); always kept as feature curves.
  std::vector<std::array<uint32_t, 2>> featureEdges;
};

//! An input corner where the input's own feature or boundary curves make a wedge below the bound
//! (features::featureWedgeAngles). Its triangles are listed and exempt from the bound: those
//! touching it, and those with an edge across its small wedge (both ends on two different curves
//! meeting at the corner, seen from it under less than the bound: the skinny triangles Ruppert's
//! concentric shells leave there, forced by the input; Shewchuk 2002).
struct ExemptCorner {
  // vertex: the input vertex; angle: its wedge, degrees; triangles: the output triangles exempt
  // for it (touching it or across its wedge)
#define CONFORMESH_X(type, name, init) type name = init;
  CONFORMESH_EXEMPT_CORNER(CONFORMESH_X)
#undef CONFORMESH_X
};

//! Wall seconds per stage of remesh(), one field per row of CONFORMESH_REMESH_STAGES
//! (conformesh/stages.h), and the whole call; the stages sum to it. Refine and lift run side by
//! side on the threads: their section's wall time is split in proportion to their thread-seconds.
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

//! remesh()'s report: one field per row of CONFORMESH_REMESH_REPORT (conformesh/remesh_schema.h).
struct RemeshReport {
#define CONFORMESH_X(type, name, init) type name = init;
  CONFORMESH_REMESH_REPORT(CONFORMESH_X)
#undef CONFORMESH_X
};

//! One patch in the plane (RemeshOptions::patches).
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
  std::vector<RemeshPatch> patches;        //!< with RemeshOptions::patches
  std::vector<uint32_t> patchOfTriangle;   //!< with RemeshOptions::patches: patch per output triangle
  //! The pull-back point of every output corner (corner c of triangle t is 3·t + c), with
  //! attributes carried or RemeshOptions::surfacePoints: the input triangle (input
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
