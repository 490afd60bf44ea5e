// conformesh — constrained Delaunay triangulation of a planar straight-line graph (stage refine).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::planar {

//! A planar straight-line graph (PSLG), the input of the CDT and of the refinement.
//!   points          2·nP doubles, x y per vertex (finite)
//!   segments        2·nS vertex indices (0-based) per segment
//!   segmentMarkers  empty, or nS integers carried to the output edges (Triangle's markers)
//!   holes           2·nH doubles: hole seed points (Triangle's .poly semantics: the region
//!                   around a seed, bounded by segments, is removed)
//! Exact duplicate points are merged: a duplicate keeps its index in the output (with its
//! coordinates) but no triangle uses it, and segments that name it use the first copy.
//! Segments that cross or overlap are rejected (Code::InvalidPslg, naming both segment
//! indices); an input vertex lying exactly on a segment splits that segment there.
struct Pslg {
  std::vector<double> points;
  std::vector<uint32_t> segments;
  std::vector<int32_t> segmentMarkers;
  std::vector<double> holes;
};

struct CdtOptions {
  //! Constrain the convex hull edges (Triangle's -c): the domain is the whole convex hull minus
  //! holes. Default false: triangles outside the outermost segments are removed ("eaten" from
  //! the hull inward up to segments, as Triangle does without -c). A PSLG without segments
  //! always gets its convex hull. An empty domain is an error (InvalidPslg).
  bool convexHull = false;
  //! Domain by orientation instead of seeds: the domain is where the winding number of the
  //! directed segments (a -> b) is non-zero, so counter-clockwise loops bound the domain and
  //! clockwise loops inside them are holes. Segments that are not part of closed loops (a
  //! vertex with unequal in/out segment degree) act as interior constraints only. Hole seeds
  //! are still applied. Inconsistent orientation gives Code::InvalidPslg.
  bool holesByOrientation = false;
};

//! A planar triangulation with its constrained edges and, per vertex, where it lies on the
//! input segments.
//!   points         2·nV: the nP input vertices first (same order), then Steiner vertices
//!   triangles      3·nT vertex indices, counter-clockwise
//!   edges          2·nE: the constrained edges of the output (subsegments of input segments,
//!                  plus convex-hull edges when CdtOptions::convexHull)
//!   edgeSegment    nE: input segment index of each constrained edge (-1: a convex-hull edge)
//!   edgeMarker     nE: that segment's marker (0 when the input has none; 1 for hull edges)
//!   vertexSegment  nV: an input segment the vertex lies on, or -1 (for input vertices the
//!                  lowest-index segment through it)
//!   vertexParam    nV: parameter t of the vertex on vertexSegment s = (a, b):
//!                  p = a + t·(b − a), t in [0, 1]; 0 when vertexSegment is -1. Steiner
//!                  vertices on segments are computed from t, so they are on the segment up
//!                  to one rounding of the coordinates.
struct PlanarMesh {
  std::vector<double> points;
  std::vector<uint32_t> triangles;
  std::vector<uint32_t> edges;
  std::vector<int32_t> edgeSegment;
  std::vector<int32_t> edgeMarker;
  std::vector<int32_t> vertexSegment;
  std::vector<double> vertexParam;

  size_t vertexCount() const { return points.size() / 2; }
  size_t triangleCount() const { return triangles.size() / 3; }
};

//! Constrained Delaunay triangulation of `pslg` (no Steiner points), restricted to the domain
//! (see CdtOptions). Exact predicates (Shewchuk 1997); Delaunay triangulation by randomized-
//! order incremental Bowyer–Watson insertion along a Hilbert curve, segments by cavity
//! retriangulation (Anglada 1997).
//! Failure: InvalidPslg (crossing/overlapping/degenerate segments, fewer than 3 distinct or
//! all collinear points), IndexOutOfRange, NonFiniteCoordinate, Cancelled.
PlanarMesh triangulatePslg(const Pslg& pslg, const CdtOptions& options = {},
                           const ProgressFn& progress = nullptr);

}  // namespace conformesh::planar
