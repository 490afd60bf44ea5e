// conformesh — optimization of a patch's planar mesh after refinement, judged in 3D (issue 9).
//
// Vertex moves toward the mean of the star's equilateral apexes (each star triangle's ideal
// place for the vertex: follows a graded mesh), the optimal Delaunay triangulation position
// (ODT: the area-weighted mean of the circumcenters of the star; Chen–Xu 2004, Alliez et al. 2005
// "Variational tetrahedral meshing"), and a half step toward the first; and edge flips; with
// OptimizeOptions::valenceOperations, flips and edge collapses toward regular valences too.
// Both are done in the conformal plane of the patch, where the planar mesh stays a valid
// triangulation, and both are accepted only when the lifted 3D triangles get better: the star's
// smallest 3D angle never drops below the bound (or below its own value when it is already under
// the bound), no planar triangle inverts, and every vertex stays on the input surface (it is
// lifted by the pull-back). Boundary vertices (curve samples) never move here, boundary edges
// never flip, and no flip makes an edge between two of them (a chord the patch across may draw
// too), so features and the stitch between patches are untouched; the pipeline slides the curve
// samples along their curves itself (remesh/slide_samples.h), in every patch at once.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "features/edge_graph.h"

namespace conformesh::optimization {

struct OptimizeOptions {
  double minAngleDeg = 30.0;  //!< the 3D angle bound a move or flip must keep
  int maxIterations = 2;      //!< passes over all vertices and edges (hard cap)
  //! Stop when a pass raises the sum of per-triangle 3D min angles by less than this fraction.
  double tolerance = 1e-3;
  //! Passes after those, over the vertices of the triangles below the bound only, as the minimal
  //! angle improvement of Hu, Yan, Bommes, Alliez and Benes (IEEE TVCG 2017) works where the
  //! angle is below the bound (a hard cap; they stop when none is left or nothing moves or
  //! flips). 0: none.
  int boundPasses = 0;
  //! A star whose smallest 3D angle is below this, and which none of the move targets (planar
  //! averages: the equilateral apexes, the ODT position) improved, gets a step up the gradient
  //! of its sum of 3D min angles (forward differences: two lifts, then up to three step
  //! lengths): where the lift bends planar shapes (curvature, or roughness at the scale of the
  //! triangles, as on a scan) the targets miss the best 3D angles, often by a short step aside.
  //! 0 (or at most minAngleDeg): none.
  double searchBelowDeg = 0.0;
  //! The valence operations: an edge also flips when that brings its four vertices' triangle
  //! counts nearer their ideal (6 inside, the planar angle sum over 60 degrees at a curve sample)
  //! with both new triangles at or above the bound, and an edge (u, w) with u free collapses
  //! into w when that brings the counts nearer (see collapsePass in optimize.cpp). A star's
  //! smallest angle is bounded by 360° over its vertex's triangle count: the 7-valent vertices
  //! of a Delaunay refinement hold the mean min angle near 51° whatever the moves do.
  bool valenceOperations = false;
  //! Edges that neither flip nor split: the constrained segments inside the patch (an inner
  //! curve's, remesh/curve_samples.h), each as keptEdgeKey(a, b), sorted. Any other edge between
  //! two fixed vertices may go (a chord across the wedge between two inner curves), and in a patch
  //! with such segments a triangle of three fixed vertices may be split on such a chord.
  std::vector<uint64_t> keptEdges;
};

//! The key of edge (a, b) in OptimizeOptions::keptEdges (either order).
inline uint64_t keptEdgeKey(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a); }
//! Edge (a, b) is one of o.keptEdges.
bool keptEdge(const OptimizeOptions& o, uint32_t a, uint32_t b);

struct OptimizeStats {
  int iterations = 0;
  size_t moves = 0, flips = 0, collapses = 0;
  double meanMinAngleBefore = 0, meanMinAngleAfter = 0;  //!< degrees, 3D (minAngleDeg3Approx)
};

//! Lift a planar point to the surface; false when it is not in the flattened patch. v: the
//! vertex being moved there (lets the lift start its point location where v's last lift landed).
using LiftFn = std::function<bool(uint32_t v, double x, double y, Vec3& out)>;

//! A guard: points of the input surface in the patch (e.g. its input vertices), planar (xy: 2 per
//! point, in the patch's plane) and 3D (pos). When given, each point is kept listed in the output
//! triangle over it in the plane, and a move or flip is kept only if no point of the triangles it
//! changes ends up farther (3D distance to the nearest of those triangles after the change) than
//! `tolerance` or, when one of them was farther than that before (distance to its triangle), than
//! the farthest was: the optimization never takes the output beyond the tolerance from these
//! points where it was within it, nor farther where it was not (a local, per-point bound on the
//! input-to-output Hausdorff distance). Points in no triangle (beyond a boundary chord) are not
//! tracked.
struct SurfaceSamples {
  std::vector<double> xy;
  std::vector<Vec3> pos;
  double tolerance = 0;  //!< 3D length
};

//! In OptimizeCache's adjacency and guard lists: no triangle (a border side, the end of a list).
constexpr uint32_t kNoTriangle = 0xffffffffu;

//! Optimize in place. xy: 2 per vertex (planar); triangles: 3 per triangle, counter-clockwise
//! in the plane; pos: 3D position per vertex (pos[v] must be the lift of xy[v]); fixed[v]: the
//! vertex does not move. Edges used by one triangle only are boundary edges and never flip.
//! active: the vertices the first pass visits (empty: all); later passes visit those whose star
//! changed in the pass before.
//! cache (optional): what the previous call on the same triangles left, for this one to reuse,
//! and on return what this call leaves. Used only with an `active` list: the caller clears it
//! when the triangles or positions changed otherwise than at `active` vertices since.
struct OptimizeCache {
  std::vector<double> minAngle;  //!< per triangle, its 3D min angle (degrees, minAngleDeg3Approx)
  std::vector<uint32_t> adjacency;  //!< per triangle side, the triangle across it
  std::vector<uint32_t> starStart, starTri;  //!< vertex -> triangles (core/vertex_stars.h); empty when stale
  //! the guard's points per triangle (a list: head per triangle, next per point) and the largest
  //! squared distance from them to the triangle; empty without a guard
  std::vector<uint32_t> guardHead, guardNext;
  std::vector<double> guardErr;
};
OptimizeStats optimizePatch(std::vector<double>& xy, std::vector<uint32_t>& triangles, std::vector<Vec3>& pos,
                            const std::vector<uint8_t>& fixed, const LiftFn& lift, const OptimizeOptions& options,
                            const std::vector<uint8_t>& active = {}, const SurfaceSamples& guard = {},
                            OptimizeCache* cache = nullptr);

//! Smallest angle of the 3D triangle (a, b, c), in degrees.
double minAngleDeg3(const Vec3& a, const Vec3& b, const Vec3& c);

//! minAngleDeg3 without atan2, within 1e-4 degrees of it (a polynomial arctangent; measured
//! within 1.2e-6); 0 for a degenerate triangle, NaN when its three corners coincide. The optimizer ranks
//! and decides its moves and flips by it, and takes minAngleDeg3 where the bound is at stake
//! (within 1e-5 degrees of it).
double minAngleDeg3Approx(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace conformesh::optimization
