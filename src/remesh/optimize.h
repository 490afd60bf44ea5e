// conformesh — optimization of a patch's planar mesh after refinement, judged in 3D (issue 9).
//
// Vertex moves toward the optimal Delaunay triangulation position (ODT: the area-weighted mean
// of the circumcenters of the star; Chen–Xu 2004, Alliez et al. 2005 "Variational tetrahedral
// meshing") and edge flips, both done in the conformal plane of the patch, where the planar mesh
// stays a valid triangulation, and both accepted only when the lifted 3D triangles get better:
// the star's smallest 3D angle never drops below the bound (or below its own value when it is
// already under the bound), no planar triangle inverts, and every vertex stays on the input
// surface (it is lifted by the pull-back). Boundary vertices (curve samples) never move and
// boundary edges never flip, so features and the stitch between patches are untouched.
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
};

struct OptimizeStats {
  int iterations = 0;
  size_t moves = 0, flips = 0;
  double meanMinAngleBefore = 0, meanMinAngleAfter = 0;  //!< degrees, 3D
};

//! Lift a planar point to the surface; false when it is not in the flattened patch. v: the
//! vertex being moved there (lets the lift start its point location where v's last lift landed).
using LiftFn = std::function<bool(uint32_t v, double x, double y, features::Vec3& out)>;

//! Optimize in place. xy: 2 per vertex (planar); triangles: 3 per triangle, counter-clockwise
//! in the plane; pos: 3D position per vertex (pos[v] must be the lift of xy[v]); fixed[v]: the
//! vertex does not move. Edges used by one triangle only are boundary edges and never flip.
OptimizeStats optimizePatch(std::vector<double>& xy, std::vector<uint32_t>& triangles, std::vector<features::Vec3>& pos,
                            const std::vector<uint8_t>& fixed, const LiftFn& lift, const OptimizeOptions& options);

//! Smallest angle of the 3D triangle (a, b, c), in degrees.
double minAngleDeg3(const features::Vec3& a, const features::Vec3& b, const features::Vec3& c);

//! minAngleDeg3 without atan2, within 1e-4 degrees of it (a polynomial arctangent); NaN for a
//! triangle whose smallest corner is degenerate. The optimizer uses it only to skip exact
//! evaluations whose outcome it already knows.
double minAngleDeg3Approx(const features::Vec3& a, const features::Vec3& b, const features::Vec3& c);

}  // namespace conformesh::optimization
