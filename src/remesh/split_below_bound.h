// conformesh — a vertex added where the optimization cannot reach the bound: a triangle still
// below it after optimizePatch, where one vertex serves too many boundary segments (a fan of
// curve samples around one interior vertex: moving it trades one side's angle for the other's),
// gets a new vertex at the midpoint of an interior edge at its smallest corner, and the
// optimization runs again around it. Kept only when the patch then has fewer triangles below the
// bound; the boundary (curve samples and their segments) is never touched, so the patches still
// stitch. The edge split of isotropic remeshing (Botsch–Kobbelt 2004), used here only as the
// minimal angle improvement of Hu, Yan, Bommes, Alliez and Benes (IEEE TVCG 2017) uses its local
// operators: where the angle is below the bound.
#pragma once

#include <cstdint>
#include <vector>

#include "remesh/optimize.h"

namespace conformesh::optimization {

struct SplitOptions {
  //! Splits tried per call at most (a hard cap: each costs a pass over the patch); reaching it
  //! is reported (SplitStats::capped).
  int maxAttempts = 64;
  //! Bound passes the optimization around a new vertex gets (OptimizeOptions::boundPasses).
  int boundPasses = 8;
};

struct SplitStats {
  size_t attempts = 0, splits = 0;  //!< tried, kept
  OptimizeStats optimize;           //!< the kept tries' optimizations, summed (moves, flips)
  bool capped = false;              //!< stopped at SplitOptions::maxAttempts with triangles left
};

//! Arrays as optimizePatch takes them (optimize.h); `fixed` grows with `xy` and `pos` (a new
//! vertex is free), and lift(v, ...) is called with v up to the new vertex count - 1. The
//! triangles below `o.minAngleDeg` (3D) are tried in index order, once per pass, and the passes
//! repeat while one keeps a split. Left alone: triangles of three fixed vertices (a strip
//! between curves, a corner's wedge), and those whose smallest corner is a fixed vertex with less
//! than the bound in all of its patch triangles (an input corner). Deterministic.
SplitStats splitBelowBound(std::vector<double>& xy, std::vector<uint32_t>& triangles, std::vector<Vec3>& pos,
                           std::vector<uint8_t>& fixed, const LiftFn& lift, const OptimizeOptions& o,
                           const SurfaceSamples& guard, const SplitOptions& so = {});

}  // namespace conformesh::optimization
