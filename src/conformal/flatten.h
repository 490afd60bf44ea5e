// conformesh — public API of the flatten stage: conformal flattening of a patch (disk or disk
// with holes) by discrete Ricci flow with intrinsic Delaunay flips, an isometric layout, and
// the exact pull-back to the input surface.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <memory>
#include <utility>
#include <vector>

#include "conformal/overlay.h"
#include "conformal/ricci_flow.h"
#include "core/mesh_buffers.h"

namespace conformesh {

using conformal::BoundaryCondition;
using conformal::Pullback;
using conformal::PullbackPoint;

struct FlattenOptions {
  //! Circle (default): a round disk, inner loops round holes (a circle domain). Free: u = 0 on
  //! the outer loop (least area distortion), inner loops circles. Corners: straight-edged
  //! polygon with the given corner angles on the outer loop (see conformal/ricci_flow.h).
  BoundaryCondition boundary = BoundaryCondition::Circle;
  //! Corners for BoundaryCondition::Corners: (vertex index, target interior angle in radians).
  std::vector<std::pair<uint32_t, double>> corners;
  bool flips = true;         //!< intrinsic Delaunay flips (disable only to study the flow without them)
  double tolerance = 1e-9;   //!< max |K - Kbar| in radians
  int maxIterations = 100;   //!< Newton cap (Code::IterationLimit)
  bool pullback = true;      //!< build the overlay and the pull-back
  //! With pullback: keep what the pull-back is built from and build it in finishPullback, so a
  //! flattening that is looked at and dropped (a patch cut again) does not pay for the overlay.
  bool deferPullback = false;
  //! Throw Code::NumericalFailure when the layout has inverted triangles or crossing boundary
  //! loops (default); false returns the result with the counts in the report.
  bool requireValidLayout = true;
  //! Circle: among the Möbius-equivalent solutions, return the one whose 3D-area-weighted
  //! vertex centroid is the disk centre (fixed-point iteration; lowers the area distortion).
  bool balanceMobius = true;
  //! Mesh edges (vertex pairs) no flip may remove, so each stays a straight segment of the
  //! layout (a patch's inner curves: remesh/curve_samples.h). The triangulation is then the
  //! constrained intrinsic Delaunay one. A pair that is no interior edge is InvalidArgument.
  std::vector<std::array<uint32_t, 2>> keepEdges;
};

struct FlattenReport {
  int iterations = 0;
  double maxCurvatureError = 0.0;     //!< final max |K - Kbar| (radians)
  std::vector<double> residuals;      //!< max |K - Kbar| before each Newton step, and at the end
  long long flips = 0;                //!< Ptolemy flips during the flow
  long long euclideanFlips = 0;       //!< flips to the intrinsic Delaunay triangulation of the input
  double seconds = 0.0;               //!< total wall time
  double secondsFlow = 0.0, secondsLayout = 0.0, secondsOverlay = 0.0;
  conformal::FlowProfile flowProfile;  //!< where the flow's time went
  double gaussBonnetError = 0.0;      //!< |sum K - 2 pi chi|
  int invertedTriangles = 0;          //!< final intrinsic triangles with signed area <= 0 in the layout
  int boundaryCrossings = 0;          //!< intersecting boundary edge pairs in the layout (0: simple, disjoint)
  //! Those pairs, each as its two edges' patch vertices (a0, a1, b0, b1).
  std::vector<std::array<uint32_t, 4>> boundaryCrossingEdges;
  //! Why the layout is not valid (inverted triangles, crossing boundary loops or edge lengths
  //! off by more than 1e-3; the message the check throws with), "" when it is.
  std::string invalidLayout;
  double layoutLengthError = 0.0;     //!< max relative edge length error of the layout
  //! Quasi-conformal ratio sigma_max / sigma_min of the affine map from each input triangle (3D)
  //! to the triangle of its vertices' uv. An estimate: the true map is projective per overlay
  //! cell, so input triangles crossed by flips are not mapped affinely.
  double angleDistortionMean = 1.0, angleDistortionMax = 1.0;
  //! Input triangles whose vertex uv triangle is inverted or degenerate (exact orientation of the
  //! uv, the triangles a mesh written with this uv has): the uv is only an estimate of the map,
  //! exact on the overlay, so a valid layout can still leave a few inverted.
  int inputTrianglesInvertedInUv = 0;
  //! Area scale e^{2u} (u normalized so the flat area equals the 3D area): min, max, max/min.
  double areaDistortionMin = 1.0, areaDistortionMax = 1.0, areaDistortionRange = 1.0;
  size_t overlayCrossings = 0;        //!< input edge / final edge crossings in the overlay
  int boundaryLoops = 0;
  //! Corners: the factor applied to the corner angles so that they close a polygon when every
  //! outer vertex is a corner (Gauss–Bonnet; 1 when the angles were used as given).
  double cornerAngleScale = 1.0;
};

struct FlatPatch {
  std::vector<double> uv;  //!< 2 per input vertex: planar position (the overlay's vertices)
  std::vector<double> u;   //!< per input vertex: log scale factor (lengths scale by e^{(u_i+u_j)/2})
  //! The final intrinsic triangulation laid out in the plane (positions z = 0), for display.
  MeshBuffers layout;
  std::vector<std::vector<uint32_t>> boundaryLoops;  //!< vertex loops, outer first, domain on the left
  Pullback pullback;       //!< planar point -> input face, barycentric coordinates, 3D point
  FlattenReport report;
  //! FlattenOptions::deferPullback: the triangulations the pull-back is built from, until
  //! finishPullback (then empty).
  std::shared_ptr<struct DeferredPullback> deferred;
};

//! Build the pull-back of a flattening made with FlattenOptions::deferPullback (and its report's
//! overlayCrossings, secondsOverlay); nothing when there is none to build. The same pull-back as
//! without deferring.
void finishPullback(FlatPatch& flat);

//! Flatten a patch conformally. Pre: a manifold, consistently oriented, connected triangle
//! mesh with genus 0 and at least one boundary loop, no zero-area faces. Vertices are never
//! inserted: uv[v] is the image of input vertex v. Algorithms: Springborn–Schröder–Pinkall 2008
//! (energy, Newton), Gillespie–Springborn–Crane 2021 and Campen et al. 2021 (Ptolemy flips,
//! overlay). Throws conformesh::Error with stage Flatten: EmptyMesh, IndexOutOfRange,
//! NonFiniteCoordinate, DegenerateFace, NonManifoldEdge, NonManifoldVertex,
//! InconsistentOrientation, InvalidTopology, InvalidArgument, IterationLimit, NotConverged,
//! NumericalFailure, Cancelled.
FlatPatch flatten(const MeshBuffers& patch, const FlattenOptions& options = {}, ProgressFn progress = {});

//! Along an input edge the flips left in place (on the boundary, or kept by
//! FlattenOptions::keepEdges), the pull-back is the projective map of that edge: the point at
//! parameter t of the planar edge from vertex a to b lands at parameter
//! s = t e^{u_b} / ((1 − t) e^{u_a} + t e^{u_b}) of the input edge (the barycentrics weighted by
//! e^u, as the pull-back's overlay takes them; Springborn, Schröder and Pinkall 2008, §4). Where
//! u_a = u_b it is affine. u: FlatPatch::u.
double edgeSurfaceParam(const std::vector<double>& u, uint32_t a, uint32_t b, double t);
//! Its inverse: the planar parameter of the point at parameter s of the input edge from a to b.
double edgePlanarParam(const std::vector<double>& u, uint32_t a, uint32_t b, double s);

//! Corners for BoundaryCondition::Corners: the vertices of the outer boundary loop (the longest)
//! whose 3D interior angle differs from pi by more than `threshold` radians, with that angle as
//! their target. Throws conformesh::Error (stage Flatten) on invalid input, like flatten().
std::vector<std::pair<uint32_t, double>> detectCorners(const MeshBuffers& patch, double threshold);

}  // namespace conformesh
