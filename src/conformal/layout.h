// conformesh — isometric layout of a flat intrinsic triangulation in the plane, and its checks.
#pragma once

#include <vector>

#include "conformal/intrinsic_triangulation.h"
#include "conformal/ricci_flow.h"

namespace conformesh::conformal {

struct LayoutResult {
  std::vector<double> xy;           //!< 2 nV planar positions
  int invertedTriangles = 0;        //!< faces with signed area <= 0
  double maxEdgeLengthError = 0.0;  //!< max relative |layout length - intrinsic length| over edges
  int boundaryCrossings = 0;        //!< pairs of boundary edges that intersect (0: loops simple, disjoint)
};

//! Lay out T with the metric u face by face, breadth-first from a central face (the face
//! farthest from the boundary in edge hops, which halves the depth of the layout tree and so
//! the accumulated round-off). Each new vertex is placed from its two known neighbours with
//! the intrinsic lengths (angles by Kahan's formula). Every vertex is placed once; the checks
//! measure how well non-tree edges close up (holonomy, round-off), whether triangles are
//! inverted, and whether the boundary loops are simple and pairwise disjoint.
LayoutResult layoutFlat(const IntrinsicTriangulation& T, const std::vector<double>& u);

//! Whether a layout of T with the metric u can be computed in double precision. Positions carry
//! round-off of about 2^-52 times the domain's size, so an edge shorter than
//! kMinRelativeEdgeLength times sqrt(flat area) cannot keep its length to the layout's 1e-3
//! check (and is useless to the planar mesher). This happens when the conformal scale factor
//! spans too many orders of magnitude: a round disk for a shape with long thin limbs crowds the
//! limbs exponentially (alligator.obj: e^{2u} spans 1e47). Throws conformesh::Error
//! NumericalFailure (stage Flatten) with the numbers and what to do otherwise.
constexpr double kMinRelativeEdgeLength = 1e-12;
void requireRepresentableLayout(const IntrinsicTriangulation& T, const std::vector<double>& u, BoundaryCondition boundary);

//! Count intersecting pairs among segments (a_k, b_k) (indices into xy), ignoring pairs that
//! share an endpoint. Uniform grid; O(n) expected for boundary polygons.
int countSegmentCrossings(const std::vector<double>& xy, const std::vector<std::pair<int, int>>& segments);

}  // namespace conformesh::conformal
