// conformesh — the data remesh()'s stages hand each other (internal; remesh/remesh.h is the API).
//
//   prepare ─► flatten patches ─► sample curves ─► rounds of: mesh patches (refine, lift,
//   optimize), slide samples, stitch, certificate ─► repair ─► report
//
// Surface is built by prepareSurface and read-only after flattenPatches (which may split its
// patches); PatchWork is one patch's state; CurveSamples the samples the patches share. Each
// stage is a free function over these (its own file), and remesh.cpp runs them in order.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "conformal/flatten.h"
#include "core/status.h"
#include "features/curve_mesh.h"
#include "features/edge_graph.h"
#include "features/patch_mesh.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "mesh/precondition.h"
#include "mesh/validate.h"
#include "remesh/optimize.h"
#include "remesh/remesh.h"
#include "remesh/spot_field.h"

namespace conformesh::pipeline {

namespace F = features;
using F::kNone;

//! The progress callback of the call: returning false cancels (Code::Cancelled).
struct Progress {
  const ProgressFn& fn;
  void check(Stage s, double fraction) const;
};

using Clock = std::chrono::steady_clock;
inline double secondsBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

//! Wall time per stage (RemeshReport::seconds): the time between two switches goes to the stage
//! that was current, and the wall time of a section whose stages run side by side on threads is
//! split among them in proportion to the seconds their items spent in each (split).
class StageClock {
 public:
  explicit StageClock(Stage first);
  //! Charge the time since the last switch to the current stage and make s current; returns the
  //! stage left (to go back to after a nested one).
  Stage enter(Stage s);
  //! Charge the time since the last switch to the stages in proportion to `busy`, the seconds a
  //! section's items spent in each stage summed over the threads (all to the current stage when
  //! busy has none); the current stage stays current. The stages still sum to the wall time.
  void split(const StageSeconds& busy);
  //! Every stage's seconds so far (the current one's up to now) and the total since construction.
  StageSeconds seconds();

 private:
  StageSeconds seconds_;
  Stage current_;
  Clock::time_point start_, last_;
};

//! The input as the stages see it: validated, preconditioned, segmented, sized.
struct Surface {
  ValidatedMesh vm;      //!< the input validated (vm.buffers); maps back to the caller's indices
  Preconditioned pre;    //!< vm.buffers after mesh/precondition.h (the first vertices are the input's)
  bool preconditioned = false;  //!< g was built from pre.mesh (else from vm.buffers: nothing changed)
  F::EdgeGraph g;
  F::Segmentation seg;
  F::SizingField sizing;
  double chordTolerance = 0;  //!< in the input's units (the sizing's, features/sizing.h)
  //! The length the refinement's boundary splits stop at a fixed fraction of (mesh_patch.cpp):
  //! the sizing's smallest length, but under an error bound, whose sizes may go below a tenth of
  //! the target near spike tips, still that tenth (two splits of one input edge told apart).
  double splitFloorLength = 0;

  const MeshBuffers& input() const { return vm.buffers; }
  //! The mesh g was built from (the same vertex and face indices).
  const MeshBuffers& graphMesh() const { return preconditioned ? pre.mesh : vm.buffers; }
};

//! A curve inside a patch (Segmentation::isInnerCurve): the patch's sub-mesh vertex at each of
//! its vertices, so its planar polyline is the layout's uv there.
struct InnerCurve {
  uint32_t curve;
  std::vector<uint32_t> sub;  //!< sub[i]: curve vertex i (the curve's vertices.size() of them)
};

//! One patch: its sub-mesh, flattening, sizing, and its latest meshing.
struct PatchWork {
  F::PatchMesh pm;
  FlatPatch flat;
  std::vector<InnerCurve> inner;  //!< its inner curves, by curve id (remesh/curve_samples.h)
  std::vector<double> hSub;      // 3D target length per sub vertex
  std::vector<double> scaleSub;  // planar length per 3D length, per sub vertex
  std::vector<Spot> spots;       // where the 3D angle certificate asks for smaller planar triangles
  std::vector<double> requiredPoints;  // planar points every refinement of the patch must contain
  // latest meshing
  std::vector<uint32_t> localToGlobal;  // planar vertex -> output vertex (samples first)
  std::vector<Vec3> interiorPositions;  // positions of planar vertices that are interior
  std::vector<int> layoutFaces;             // per planar vertex: the flattened face of its lift, -1 none
  std::vector<uint32_t> liftFaces;          // per planar vertex: the input (g) face of its latest lift, kNone none
  optimization::OptimizeCache optimizeCache;  // the latest optimizePatch's, for the next one on this meshing
  std::vector<uint32_t> triangles;         // planar triangles (local indices)
  std::vector<double> planarPoints;        // planar positions of the latest meshing
  uint64_t builtAt = 0;
  bool needsMesh = true;  // full refinement (first time, or the certificate asked for spots)
  bool dirty = false;     // a neighbour added curve samples on this patch's boundary
  bool optimized = false;  // the latest meshing went through optimizePatch
  // refine without splitting the boundary: a stitch defect (a corner wedge both patches close
  // with one triangle, a chord both have) is still there at the certificate's cap. The splits a
  // required point inside it causes on the wedge's sides usually open it with good angles within
  // a few rounds, but they can also close it again closer to the corner every time
  bool keepBoundary = false;
  double slabHalfWidth = -1;  // largest distance of the patch's input vertices from their mean plane (-1: not yet known)
};

using Patches = std::vector<std::unique_ptr<PatchWork>>;

//! The curve samples every patch shares, indexed by input edge and vertex.
struct CurveSamples {
  F::CurveMesh cm;
  std::vector<std::vector<uint32_t>> edgeSamples;  //!< interior samples per input edge
  std::vector<uint32_t> vertexSample;              //!< sample at an input vertex, kNone
  std::vector<uint32_t> edgeIndexInCurve;          //!< an edge's position in its curve
  uint64_t stamp = 0;  //!< bumped by every meshing and new sample: a patch built before a sample on its boundary is dirty
};

//! The rounds' mutable state: the patches, their shared samples, and what the report sums.
struct Meshing {
  Patches patches;
  CurveSamples samples;
  //! per vertex of the edge graph: the smallest wedge (degrees) between the input's own feature
  //! and boundary curves there (features::featureWedgeAngles), and whether it is an input corner
  //! below the angle bound: an exempt corner, whose sides' triangles are left as the wedge forces
  //! them, in the plane (mesh_patch.cpp) as in 3D (certificate.h). Measured by measureCorners.
  std::vector<double> cornerWedgeDeg;
  std::vector<uint8_t> smallCorner;
};

}  // namespace conformesh::pipeline
