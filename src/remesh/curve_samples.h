// conformesh — the curve samples seen from a patch: its boundary as a polygon of samples in its
// plane, and a refinement's split of a boundary segment made a new sample that every patch on
// that curve must take up.
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! A piece of a patch's boundary polyline: boundary halfedge k of the loop, from parameter t0 to
//! t1 along it.
struct Piece {
  uint32_t k;
  double t0, t1;
};

//! A curve sample on a patch's boundary, with its place on the loop and its planar position.
struct BoundaryPoint {
  uint32_t sample;
  uint32_t loopPos;  // boundary halfedge index in the loop
  double param;      // along that halfedge from its tail
  double x, y;
};

//! Index cs.cm's samples by input edge and vertex (after sampleCurves).
void indexSamples(const Surface& surf, CurveSamples& cs);

//! The samples on a patch's boundary loop, in loop order.
std::vector<BoundaryPoint> boundaryPoints(const Surface& surf, const CurveSamples& cs, const PatchWork& w);

//! Position of sample `sample` along curve c: edge index plus the parameter within it.
double curveKey(const Surface& surf, const CurveSamples& cs, uint32_t c, uint32_t sample);

//! The pieces of the boundary polyline from boundary point p0 to the next one, p1 (`points`
//! boundary points in all).
std::vector<Piece> stretch(const PatchWork& w, const BoundaryPoint& p0, const BoundaryPoint& p1, size_t points);

//! A refinement vertex inserted on boundary segment `segment` (from boundary point segment to
//! segment + 1) at parameter t: find it on the patch boundary polyline in the plane, make it a
//! curve sample on the input edge there, and mark the patches on the curve dirty so they take it
//! up. Returns the sample (an existing one where the point is one already).
uint32_t addSplitSample(const Surface& surf, CurveSamples& cs, Patches& patches, const PatchWork& w,
                        const std::vector<BoundaryPoint>& bp, uint32_t segment, double t);

}  // namespace conformesh::pipeline
