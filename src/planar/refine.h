// conformesh — planar Delaunay refinement (stage refine).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/mesh_buffers.h"
#include "core/status.h"
#include "planar/cdt.h"

namespace conformesh::planar {

//! No apex and no chain (RefineOptions::apexOf, chainOf).
constexpr uint32_t kNoApex = 0xFFFFFFFFu;

//! Options of refinePslg. Sizes are in the units of the input coordinates.
struct RefineOptions {
  //! Angle bound θ in degrees: every triangle that is not exempt gets its smallest angle ≥ θ.
  //! Range [0, 34]; 0 switches the angle criterion off (size only).
  double minAngleDeg = 30.0;
  //! A higher angle bound for the triangles whose three vertices lie on segments (ends of input
  //! segments, or segment splits), for a caller that moves every other vertex afterwards (an
  //! optimization can raise the other triangles, not these). Range [0, 40]; at or below
  //! minAngleDeg it changes nothing. Such a triangle gets its circumcenter or off-center like any
  //! bad triangle, which adds a free vertex (or splits the segments it would encroach upon).
  double segmentTriangleMinAngleDeg = 0.0;
  //! Largest allowed triangle area (Triangle's -a). 0: no area bound.
  double maxArea = 0.0;
  //! Largest allowed edge length: a triangle is split while its longest edge exceeds
  //! the size h at its centroid, h = min(maxEdge, sizing(centroid), interpolated vertexSizing).
  //! 0: no bound.
  double maxEdge = 0.0;
  //! Sizing field h(x, y) > 0 (max edge length at that point); empty: none. Non-finite or
  //! non-positive values mean "no bound here".
  std::function<double(double, double)> sizing;
  //! Per-input-vertex sizes (empty, or one per input point): interpolated linearly
  //! (barycentric in the triangle, or along the segment) to every Steiner vertex.
  std::vector<double> vertexSizing;
  //! Insert off-centers (Üngör 2004/2009) instead of circumcenters for skinny triangles:
  //! far fewer Steiner points for the same angle bound.
  bool offcenters = true;
  //! The off-center sits at distance offcenterFactor·|pq| / (2·tan(θ/2)) from the midpoint of
  //! the shortest edge pq (1 = the exact off-center of Üngör; a little less keeps the new
  //! triangle's angle strictly above θ despite rounding). Range (0, 0.99]: at 1 a new triangle
  //! can land exactly on the bound and refinement may not terminate.
  double offcenterFactor = 0.95;
  //! Encroachment by diametral lenses (a point encroaches upon a subsegment when it sees it
  //! under more than 180° − 2θ; Chew 1989, Shewchuk 2002) instead of diametral circles
  //! (more than 90°). Default off: with off-centers and shortest-edge-first order, circles
  //! gave ~9% fewer triangles on data/pslg/wiggly5000 (the lens splits fewer segments but
  //! needs more interior vertices). Circles when θ = 0.
  bool diametralLens = false;
  //! Split encroached subsegments (Ruppert). false: segments are kept as given (no Steiner
  //! vertex on them); a bad triangle whose new vertex would encroach upon a segment is then left
  //! as it is (it counts in minAngleDeg, not as exempt). For meshing several domains that
  //! share their boundary points when one of them may no longer add points there.
  bool splitSegments = true;
  //! Subsegments shorter than this are never split (absolute; 0: 1e-11 times the bounding-box
  //! diagonal, the default floor). A bad triangle that would need such a split stays.
  double minSegmentLength = 0.0;
  //! Small input corners no mesh can give better angles, whose sides are chains of several
  //! segments (a caller's input corner with its sides sampled): per input point, the input point
  //! that is its corner (apex) and the id of the chain it lies on; empty, or kNoApex where none. A
  //! triangle whose shortest edge joins points of two different chains of one apex, at distances
  //! from it within a factor 2 of each other, and seen from it under less than θ, is exempt: the
  //! wedge forces its angle (the concentric shells' rule for sides that are chains). A vertex
  //! on one chain does not encroach upon the subsegments of another chain of its apex: splitting
  //! them would only fill the wedge with more and smaller such triangles.
  std::vector<uint32_t> apexOf, chainOf;
  //! Hard cap on Steiner vertices; hitting it stops with status IterationLimit (mesh kept).
  size_t maxInsertions = 100000000;
  //! Domain options of the CDT (convex hull, holes by orientation).
  CdtOptions cdt;
  //! Progress in [0, 1] (estimated) and cancel: returning false stops with Code::Cancelled.
  ProgressFn progress;
};

//! Result of refinePslg. `mesh` follows PlanarMesh (input vertices first, constrained edges
//! with their input segment, per-vertex segment and parameter).
struct RefineResult {
  PlanarMesh mesh;
  //! Ok, or IterationLimit when maxInsertions stopped the refinement (the mesh is valid but
  //! not every triangle meets the bounds).
  Status status;
  //! Smallest angle (degrees) over the triangles that are not exempt.
  double minAngleDeg = 0.0;
  //! Triangles below θ whose small angle is forced by the input: the angle is an input
  //! angle between two segments (< θ), or the shortest edge joins two segment vertices on
  //! segments sharing an apex at equal distance from it (concentric shells; Shewchuk 2002).
  size_t exemptTriangles = 0;
  size_t insertions = 0;      //!< Steiner vertices inserted (all kinds)
  size_t segmentSplits = 0;   //!< of which on segments
  size_t rejected = 0;        //!< insertion points given up (duplicate, cavity not star-shaped, tiny segment)
  double seconds = 0.0;       //!< wall time of the whole call
};

//! Constrained Delaunay refinement of a PSLG (Ruppert 1995; Shewchuk 2002 "Delaunay refinement
//! algorithms for triangular mesh generation"): encroached subsegments (diametral circle) are
//! split first, at the midpoint, or at a power-of-two distance from an input vertex shared
//! with another segment (concentric shells, so refinement terminates at small input angles);
//! then bad triangles, shortest edge first, get their off-center / circumcenter, which is
//! rejected in favour of splitting the subsegments it would encroach.
//! Quality: min angle ≥ θ except exempt triangles; size: area ≤ maxArea and longest edge ≤ h.
//! Limits (measured): inputs whose angles are all ≥ 60° meet θ up to 34°; with smaller input
//! angles θ ≤ 30° was met on every input tried (1000 random spiky polygons), while at 33° about
//! 5% of them keep a few triangles below θ next to a small input angle (segment pieces that
//! would get shorter than 1e-11 × the bounding-box diagonal are not split). Such triangles are
//! not counted as exempt: minAngleDeg reports them. Refinement always stops (insertion cap).
//! Failure: as triangulatePslg; InvalidArgument (θ outside [0, 34], negative sizes, wrong
//! vertexSizing length); Cancelled. IterationLimit is returned in `status`, not thrown.
RefineResult refinePslg(const Pslg& pslg, const RefineOptions& options = {});

}  // namespace conformesh::planar
