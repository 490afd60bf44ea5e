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

//! A curve sample on a patch's boundary loop or on one of its inner curves, with its place there
//! and its planar position.
struct BoundaryPoint {
  uint32_t sample;
  uint32_t loopPos;  // boundary halfedge index in the loop; on an inner curve, the curve's edge
  double param;      // along that halfedge from its tail; on an inner curve, along the curve
  double x, y;
  uint32_t inner = kNone;  // index in PatchWork::inner of a point on an inner curve; kNone: on the loop
};

//! A segment of a patch's planar domain on one of its inner curves: from point a to point b of
//! its boundary points, over the curve from key ka to key kb (edge index plus the parameter
//! within it, ka < kb).
struct InnerSegment {
  uint32_t a, b;
  uint32_t inner;  // index in PatchWork::inner
  double ka, kb;
};

//! Index cs.cm's samples by input edge and vertex (after sampleCurves).
void indexSamples(const Surface& surf, CurveSamples& cs);

//! The inner curves of patch mesh pm (Segmentation::isInnerCurve), by curve id.
std::vector<InnerCurve> innerCurves(const Surface& surf, const F::PatchMesh& pm);

//! The samples on a patch's boundary loop, in loop order, then those on its inner curves not on
//! the loop (each sample once), curve by curve; `inner` (when given) gets the segments between
//! consecutive samples of each inner curve.
std::vector<BoundaryPoint> boundaryPoints(const Surface& surf, const CurveSamples& cs, const PatchWork& w,
                                          std::vector<InnerSegment>* inner = nullptr);

//! How many of a patch's boundary points are on its loop (they come first).
size_t loopPointCount(const std::vector<BoundaryPoint>& bp);

//! Position of sample `sample` along curve c: edge index plus the parameter within it.
double curveKey(const Surface& surf, const CurveSamples& cs, uint32_t c, uint32_t sample);

//! The pieces of the boundary polyline from boundary point p0 to the next one, p1 (`points`
//! boundary points in all).
std::vector<Piece> stretch(const PatchWork& w, const BoundaryPoint& p0, const BoundaryPoint& p1, size_t points);

//! A refinement vertex inserted on segment `segment` of the patch's domain at parameter t: a loop
//! segment (from boundary point `segment` to the next on the loop) or, from the loop's point
//! count on, inner segment `segment` minus that count. Find it on the patch's polyline in the
//! plane, make it a curve sample on the input edge there, and mark the patches on the curve dirty
//! so they take it up. Returns the sample (an existing one where the point is one already).
uint32_t addSplitSample(const Surface& surf, CurveSamples& cs, Patches& patches, const PatchWork& w,
                        const std::vector<BoundaryPoint>& bp, const std::vector<InnerSegment>& inner,
                        uint32_t segment, double t);

}  // namespace conformesh::pipeline
