// conformesh — output size limits of remesh: a prediction of the output size and of the memory the
// pipeline needs, made from the sizing field before the heavy work (flatten, refine), and the check
// of the real counts after refinement. Exceeding a limit is Code::TooLarge, never an allocation
// failure deep inside the pipeline.
#pragma once

#include <cstddef>

#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "remesh/remesh.h"

namespace conformesh {

//! What remesh is predicted to produce and need.
struct OutputEstimate {
  double triangles = 0;  //!< output triangles
  double vertices = 0;   //!< output vertices
  double bytes = 0;      //!< peak heap bytes of the whole remesh call
};

//! Peak memory per input triangle and per output triangle of a remesh call: the native CLI's
//! peak RSS, rounded up for the WASM heap, which grows by doubling vectors and never shrinks
//! (docs/decisions/0018-output-limits.md).
constexpr double kBytesPerInputTriangle = 1500.0;
constexpr double kBytesPerOutputTriangle = 250.0;

//! Real output triangles per equilateral-triangle estimate: the refinement's angle bound and the
//! curve samples add triangles (the median of three models: docs/decisions/0018).
constexpr double kTrianglesPerEquilateral = 1.3;

//! Predict the output of remesh from the sizing field (before flattening and refinement).
//!   triangles = 1.3 · ∫ 1 / (√3/4 · h²) over the surface: the number of equilateral triangles of
//!               the local target edge length h, times kTrianglesPerEquilateral. The integral has
//!               two parts:
//!               - the field as computed, Σ over input faces f of area(f) / (√3/4 · h_f²), with
//!                 1/h_f² the mean of 1/h² at the face's corners;
//!               - the grading the angle bound needs at thin features: where a patch is narrower
//!                 across from a boundary edge or an inner curve than h there
//!                 (features/patch_width.h), the
//!                 refinement samples the edge at that width w and grows the sizes away from it
//!                 at the field's gradation slope k, up to h or halfway across the patch. The
//!                 excess over h of that field, integrated in closed form along the edge and
//!                 away from it on each side (its own width w_s there):
//!                 len · [(1/k)(1/a − 1/(a + k·D)) − D/h²], a = min(h, w), D = min((h − a)/k, w_s/2);
//!   vertices  = triangles / 2 + Σ over boundary edges of length / h (closed surfaces have
//!               V ≈ F/2; every boundary sample adds half a vertex more);
//!   bytes     = kBytesPerInputTriangle · input triangles + kBytesPerOutputTriangle · triangles.
//! A prediction, not a bound: the real counts are checked again after refinement. Pre: sizing.h
//! has one positive value per vertex of g; seg is g's segmentation.
OutputEstimate estimateOutput(const features::EdgeGraph& g, const features::Segmentation& seg,
                              const features::SizingField& sizing);

//! A first estimate from the target edge length alone (curvature only adds triangles), for the
//! checks before the input is preconditioned: the same formulas with h = target everywhere.
OutputEstimate estimateFromTarget(double area, double target, size_t inputTriangles);

//! Throws Error(InvalidArgument, Api) when a limit option is 0 or NaN (0 does not mean "no
//! limit": pass a huge value for that), and Error(TooLarge, CurveMesh) when the estimate exceeds
//! maxTriangles, maxVertices or maxMemoryBytes; the message gives the estimate and the limit.
void checkOutputEstimate(const OutputEstimate& estimate, const RemeshOptions& options);

//! Throws Error(TooLarge, Stitch) when the real output exceeds maxVertices or maxTriangles.
void checkOutputCounts(size_t vertices, size_t triangles, const RemeshOptions& options);

}  // namespace conformesh
