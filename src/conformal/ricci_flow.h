// conformesh — discrete conformal metric by vertex scaling (discrete Ricci flow / Yamabe
// flow), solved by Newton's method with intrinsic Delaunay (Ptolemy) flips.
//
// Springborn–Schröder–Pinkall 2008 "Conformal equivalence of triangle meshes": for vertex
// scale factors u the scaled log lengths are lam~_ij = lam_ij + u_i + u_j; the energy E(u) is
// convex with gradient K(u) - Kbar and Hessian the cotangent Laplacian
// L_ij = -1/2 (cot a_ij + cot b_ij). Gillespie–Springborn–Crane 2021 "Discrete conformal
// equivalence of polyhedral surfaces" (and Campen et al. 2021 for boundaries): keeping the
// triangulation intrinsically Delaunay for the current metric by Ptolemy flips makes E convex
// and C2 over all of R^n, so Newton converges for every input (no triangle inequality breaks).
#pragma once

#include <utility>
#include <vector>

#include "conformal/intrinsic_triangulation.h"
#include "conformesh/remesh_schema.h"
#include "core/mesh_buffers.h"

namespace conformesh::conformal {

//! Target curvature along the boundary.
//!  Circle:  interior Kbar = 0; the outer loop becomes a circle, inner loops circles (a circle
//!           domain). The geodesic curvature at each boundary vertex is that of the polygon
//!           inscribed in a circle with the current boundary edge lengths (fixed point updated
//!           every Newton step), so every loop closes exactly (no translational holonomy).
//!  Free:    u = 0 on the outer loop (Dirichlet; least area distortion), inner loops circles.
//!  Corners: Kbar = pi - angle at the given corners of the outer loop; the rest of the outer
//!           turning (2 pi - sum) is spread over the other outer vertices by arc length (0 when
//!           the corners sum to 2 pi: a straight-edged polygon); inner loops circles. When every
//!           outer vertex is a corner, the angles are scaled by (n - 2) pi / sum to satisfy
//!           Gauss–Bonnet (FlowResult::cornerAngleScale).
using BoundaryCondition = conformesh::BoundaryCondition;  // public: conformesh/remesh_schema.h

//! "circle", "free boundary" or "corner-preserving", for messages.
inline const char* boundaryName(BoundaryCondition b) {
  return b == BoundaryCondition::Circle ? "circle" : b == BoundaryCondition::Free ? "free boundary" : "corner-preserving";
}

struct FlowOptions {
  BoundaryCondition boundary = BoundaryCondition::Circle;
  //! Corners (vertex index, target interior angle in radians, in (0, 2 pi)); only with Corners.
  std::vector<std::pair<int, double>> corners;
  bool flips = true;          //!< keep the triangulation intrinsically Delaunay (recommended)
  double tolerance = 1e-9;    //!< stop at max |K - Kbar| <= tolerance (radians)
  int maxIterations = 100;    //!< Newton iterations cap -> Code::IterationLimit
  int maxHalvings = 40;       //!< line search cap -> Code::NotConverged
};

//! Where the flow spends its time (wall seconds per phase, and counts), for benchmarks.
struct FlowProfile {
  double flips = 0;      //!< Delaunay flip passes
  double angles = 0;     //!< angles, curvature, targets
  double assemble = 0;   //!< cotangent Laplacian values
  double analyze = 0;    //!< symbolic analysis (ordering, elimination tree)
  double factor = 0;     //!< numeric factorization
  double solve = 0;      //!< triangular solves, GMRES included
  int evaluations = 0, analyses = 0, factorizations = 0, solves = 0;
};

struct FlowResult {
  std::vector<double> u;          //!< per vertex log scale factor (lengths scale by e^{(u_i+u_j)/2})
  std::vector<double> residuals;  //!< max |K - Kbar| before each iteration and at the end
  std::vector<double> steps;      //!< accepted step length per iteration
  int iterations = 0;
  long long flips = 0;
  double maxError = 0.0;
  double gaussBonnetError = 0.0;  //!< |sum K - 2 pi chi| at the end
  int outerLoop = 0;              //!< index of the outer loop in T.loops
  std::vector<double> Kbar;       //!< final target curvature per vertex
  //! Corners: factor applied to the corner angles to satisfy Gauss–Bonnet when every outer
  //! vertex is a corner (1: the angles were used as given).
  double cornerAngleScale = 1.0;
  FlowProfile profile;
};

//! Run Newton's method on T (flipped in place). The Newton systems are solved by preconditioned
//! Krylov methods with one sparse Cholesky factor of the Laplacian reused across iterations
//! (see ricci_flow.cpp). Throws conformesh::Error (stage Flatten): IterationLimit (iteration or
//! flip cap), NotConverged (line search stalls, e.g. without flips when the triangle inequality
//! breaks; or an equation held by the gauge misses the tolerance), NumericalFailure
//! (factorization; or the gauge equation is lost because the scale factors span more than double
//! precision resolves, with the numbers), InvalidArgument (bad corners), Cancelled (progress
//! returned false).
FlowResult runRicciFlow(IntrinsicTriangulation& T, const FlowOptions& options, const ProgressFn& progress = {});

//! Corner angles (angle[h] opposite halfedge h) for the metric u; returns the number of faces
//! violating the triangle inequality.
int computeAngles(const IntrinsicTriangulation& T, const std::vector<double>& u, std::vector<double>& angle);

//! Discrete Gaussian curvature per vertex: 2 pi - sum of angles inside, pi - sum on the boundary.
std::vector<double> vertexCurvature(const IntrinsicTriangulation& T, const std::vector<double>& angle);

//! Flip until every interior edge is Delaunay for the metric u (opposite angles sum <= pi).
//! Ptolemy flips by default; `euclidean` flips keep the PL metric (u must be 0), as for the
//! intrinsic Delaunay triangulation of the input (Gillespie–Springborn–Crane 2021 start from it,
//! which makes the result independent of how a flat region was triangulated).
//! Returns the flips done; throws IterationLimit above `maxFlips`.
long long flipToDelaunay(IntrinsicTriangulation& T, const std::vector<double>& u, long long maxFlips, bool euclidean = false);

//! Whether every flippable interior edge satisfies the Delaunay condition (tolerance 1e-9 rad).
bool isDelaunay(const IntrinsicTriangulation& T, const std::vector<double>& u);

}  // namespace conformesh::conformal
