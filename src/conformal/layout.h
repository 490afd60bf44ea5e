// conformesh — isometric layout of a flat intrinsic triangulation in the plane, and its checks.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "conformal/intrinsic_triangulation.h"
#include "conformal/ricci_flow.h"

namespace conformesh::conformal {

struct LayoutResult {
  std::vector<double> xy;           //!< 2 nV planar positions
  int invertedTriangles = 0;        //!< faces with signed area <= 0
  double maxEdgeLengthError = 0.0;  //!< max relative |layout length - intrinsic length| over edges
  int boundaryCrossings = 0;        //!< pairs of boundary edges that intersect (0: loops simple, disjoint)
  //! The intersecting pairs of boundary edges, each as its two edges' vertices (a0, a1, b0, b1).
  std::vector<std::array<int, 4>> crossingEdges;
};

//! Lay out T with the metric u face by face, breadth-first from a central face (the face
//! farthest from the boundary in edge hops, which halves the depth of the layout tree and so
//! the accumulated round-off). Each new vertex is placed from its two known neighbours with
//! the intrinsic lengths (angles by Kahan's formula). Every vertex is placed once; the checks
//! measure how well non-tree edges close up (holonomy, round-off), whether triangles are
//! inverted, and whether the boundary loops are simple and pairwise disjoint.
LayoutResult layoutFlat(const IntrinsicTriangulation& T, const std::vector<double>& u);

//! Why a layout of T with the metric u may be beyond double precision, or "" when it is not
//! suspect. Positions carry round-off relative to their distance from the layout's origin, so
//! an edge shorter than kMinRelativeEdgeLength times sqrt(flat area) keeps its digits only near
//! the origin (the central face). This happens when the conformal scale factor spans too many
//! orders of magnitude: a round disk for a shape with long thin limbs crowds the limbs
//! exponentially (alligator.obj: e^{2u} spans 1e47, its legs and tail at the rim). Used to
//! explain a failed layout check or a gauge equation lost to round-off; not a check by itself
//! (blade.off's free boundary map has edges 1e-20 of its size near the origin and lays out).
constexpr double kMinRelativeEdgeLength = 1e-12;
std::string scaleDiagnosis(const IntrinsicTriangulation& T, const std::vector<double>& u, BoundaryCondition boundary);

//! The intersecting pairs among segments (a_k, b_k) (indices into xy), ignoring pairs that share
//! an endpoint, as pairs of segment indices (i < j, sorted). Uniform grid; O(n) expected for
//! boundary polygons.
std::vector<std::pair<int, int>> segmentCrossings(const std::vector<double>& xy, const std::vector<std::pair<int, int>>& segments);
inline int countSegmentCrossings(const std::vector<double>& xy, const std::vector<std::pair<int, int>>& segments) {
  return int(segmentCrossings(xy, segments).size());
}

}  // namespace conformesh::conformal
