// conformesh — the 3D sizing field: target edge length per input vertex.
#pragma once

#include <cstdint>
#include <vector>

#include "features/edge_graph.h"
#include "features/segmentation.h"

namespace conformesh::features {

//! Sizing options. Lengths are in the input's units unless marked relative (to the bounding-box
//! diagonal).
struct SizingOptions {
  //! Target edge length in flat regions (absolute). <= 0: use targetEdgeLengthRel.
  double targetEdgeLength = 0;
  //! Target edge length relative to the bbox diagonal, used when targetEdgeLength <= 0.
  double targetEdgeLengthRel = 0.01;
  //! Chord tolerance (absolute): an edge of length h on a surface or curve of radius r deviates
  //! by about h²/(8r), so h <= sqrt(8 r tol). < 0: use chordToleranceRel; 0: no curvature sizing.
  double chordTolerance = -1;
  double chordToleranceRel = 1e-3;
  //! Ratio bound between neighbouring edge lengths (h grows at most by (gradation − 1) per unit
  //! of distance). Must be > 1.
  double gradation = 1.5;
  //! Clamps (absolute). < 0: minEdgeLength = target/10, maxEdgeLength = target.
  double minEdgeLength = -1;
  double maxEdgeLength = -1;
  //! Optional per-input-vertex target lengths (absolute); empty, or one per input vertex.
  std::vector<double> vertexSizing;
  //! Optional surface curvature per vertex (surfaceCurvature of the mesh the graph was made
  //! from by splits and flips, carried to the new vertices); empty: surfaceCurvature(g).
  std::vector<double> surfaceKappa;
  //! Bound the error at cone tips: off the curves, a vertex whose neighbours lie off its tangent
  //! plane by a slope s (the largest |n·d|/|d| over its edges) is a cone's tip to an output that
  //! spans it, which cuts it off by about s times its distance to the output's nearest vertex: a
  //! linear error, where the curvature bound models a quadratic one. h ≤ √3·tol / s there (an
  //! output vertex within the circumradius h/√3 of the tip). Tighter than the curvature bound only
  //! where a neighbour lies more than 3/4 tol off the plane.
  bool coneTips = false;
  //! Vertices from this index on are points that halve an edge of the mesh the graph was made
  //! from: a curve's turn at a vertex is measured to the nearest vertices along it below this
  //! index (the edges as given), so splits do not change it.
  uint32_t firstSplitVertex = UINT32_MAX;
};

struct SizingField {
  std::vector<double> h;  //!< per input vertex
  double target = 0;      //!< resolved target edge length
  double diagonal = 0;    //!< bbox diagonal
  double minLength = 0, maxLength = 0;
  double gradation = 1.5;  //!< the option used
};

//! Per vertex, the largest normal curvature 2|n·d|/|d|² over its edges d (n: the area-weighted
//! vertex normal; 0 where it vanishes). It grows without bound along short edges where n tilts off
//! a flat face, so it is measured on the input as given, not on a copy with split edges.
std::vector<double> surfaceCurvature(const EdgeGraph& g);

//! Per vertex, the largest slope |n·d|/|d| of its edges d off its tangent plane (n: the
//! area-weighted vertex normal; 0 where it vanishes): SizingOptions::coneTips.
std::vector<double> surfaceSlope(const EdgeGraph& g);

//! Bounding-box diagonal of the mesh.
double boundingBoxDiagonal(const EdgeGraph& g);

//! Compute the sizing field: min(target, curvature size, user size) clamped, then graded.
//! Curvature: smooth vertices from the osculating circle through each neighbour
//! (κ ≈ 2|n·d|/|d|²), curve vertices from the polyline's turning angle. Throws
//! Error(InvalidArgument) for bad options.
SizingField computeSizing(const EdgeGraph& g, const Segmentation& seg, const SizingOptions& options);

}  // namespace conformesh::features
