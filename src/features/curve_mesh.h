// conformesh — curve meshing: every curve sampled once in 3D, shared by the patches on both sides.
#pragma once

#include <cstdint>
#include <vector>

#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/sizing.h"

namespace conformesh::features {

//! A point exactly on an input edge: p = (1 − t)·P[edgeVerts[edge][0]] + t·P[edgeVerts[edge][1]].
//! When the sample is an input vertex (a corner), `vertex` is it and t is 0 or 1.
struct CurveSample {
  uint32_t edge = kNone;
  double t = 0;
  uint32_t vertex = kNone;
  Vec3 position;
};

//! All curve samples. Corner samples are shared by every curve ending there.
//!   samples          every sample once (the output keeps one vertex per sample)
//!   curveSamples[c]  sample ids along curve c from curves[c].vertices.front() to .back()
//!   cornerSample[v]  sample id of corner vertex v, kNone for other vertices
struct CurveMesh {
  std::vector<CurveSample> samples;
  std::vector<std::vector<uint32_t>> curveSamples;
  std::vector<uint32_t> cornerSample;
};

//! Sample every curve by arc length so that consecutive samples are about h apart, h the sizing
//! field interpolated linearly along each edge (segment count n = round(∫ ds / h), samples at
//! equal steps of ∫ ds / h). At least one segment per curve; more where needed so no two curves
//! give the same chord and every patch boundary has at least three samples; and one at the
//! curve's first (last) vertex after a corner when the chord from the corner to the next sample
//! would close a wedge there below seg.angleBoundDeg that the curve's first edge keeps open (3D
//! angles to the other curves' first edges at the corner).
CurveMesh sampleCurves(const EdgeGraph& g, const Segmentation& seg, const SizingField& sizing);

}  // namespace conformesh::features
