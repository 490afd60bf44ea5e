// conformesh — remesh stage 3, per patch: the Delaunay refinement of its boundary samples in its
// plane (planar/refine.h), the lift of every new vertex onto the input (conformal/overlay.h),
// and the optimization of the result judged in 3D (remesh/optimize.h).
#pragma once

#include "remesh/curve_samples.h"
#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! Refine patch p from scratch with its spots and required points; a boundary split becomes a
//! curve sample the patches on that curve take up (curve_samples.h). splitSegments = false keeps
//! the boundary as it is. The seconds of its refinement and of its lift are added to busy.refine
//! and busy.lift (StageClock::split). Fails with the refinement's status (IterationLimit at its
//! cap), NumericalFailure when a vertex cannot be lifted, InternalError for a boundary that is no
//! polygon.
void meshPatch(const Surface& surf, const RemeshOptions& opt, Meshing& m, uint32_t p, StageSeconds& busy,
               bool splitSegments = true);

//! A meshing of one patch made apart from the others: its refinement from the boundary points
//! bp and the lift of its vertices, but for the boundary splits, which become curve samples only
//! when it is committed (commitMeshing).
struct PatchMeshing {
  struct Split {
    uint32_t vertex;   //!< planar vertex on boundary segment `segment` (from bp[segment] to the next)
    uint32_t segment;  //!< of the patch's domain (addSplitSample's numbering)
    double t;          //!< its parameter along the segment
  };
  std::vector<BoundaryPoint> bp;  //!< the patch's boundary points it was made from
  std::vector<InnerSegment> inner;  //!< the segments of its inner curves (curve_samples.h)
  //! bp make no polygon, or their chords cross: meshPatch repairs them by adding samples, which
  //! cannot be made apart
  bool needsRepair = false;
  std::vector<Split> splits;
  std::vector<double> planarPoints;
  std::vector<uint32_t> triangles;
  std::vector<Vec3> interiorPositions;
  std::vector<int> layoutFaces;
  std::vector<uint32_t> liftFaces;
  double refineSeconds = 0, liftSeconds = 0;  //!< spent refining and lifting, on its thread
};

//! meshPatch's refinement and lift of patch p from the samples as they are, writing nothing:
//! patches may be refined apart on several threads while the samples do not change. Committed
//! (commitMeshing) while the patch's boundary points are still r.bp, it gives patch p exactly
//! what meshPatch would. Fails as meshPatch does (but for needsRepair).
PatchMeshing refineApart(const Surface& surf, const RemeshOptions& opt, const Meshing& m, uint32_t p, bool splitSegments);

//! Make r (from refineApart, not needsRepair) patch p's meshing, as meshPatch would have: its
//! boundary splits become curve samples, in vertex order. Its seconds are added to `busy`.
void commitMeshing(const Surface& surf, Meshing& m, uint32_t p, PatchMeshing& r, StageSeconds& busy);

//! What optimizeMesh did, to be added to the report.
struct OptimizeResult {
  size_t moves = 0, flips = 0;
  size_t splits = 0;          //!< vertices added where moves and flips left the bound (split_below_bound.h)
  size_t collapses = 0;       //!< edges collapsed toward regular valences (OptimizeOptions::valenceOperations)
  bool splitsCapped = false;  //!< the splits stopped at their cap with triangles below the bound left
};

//! Optimize patch w's latest meshing in its plane, judged in 3D; `active` (empty: all) the
//! vertices that may move. Writes only w: patches may be optimized on several threads.
OptimizeResult optimizeMesh(const Surface& surf, const RemeshOptions& opt, const CurveSamples& samples, PatchWork& w,
                            const std::vector<uint8_t>& active = {});

}  // namespace conformesh::pipeline
