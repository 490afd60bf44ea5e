// conformesh — overlay of the input triangulation and the final (flipped) intrinsic one, and the
// exact pull-back from the flattened domain to the input surface.
//
// Gillespie–Springborn–Crane 2021 / Campen et al. 2021: a decorated triangulation is a
// hyperbolic surface with horocycles; every triangle, input or final, is an ideal hyperbolic
// triangle, and the discrete conformal map is projective on each of them (it is the projective
// map taking the triangle's circumcircle to the absolute). We work in the hyperboloid model:
// a decorated ideal vertex is a light-like vector v with -<v_i, v_j> = e^{lam_ij}; a point of a
// triangle with Euclidean barycentric coordinates (a, b, c) is the vector a v_i + b v_j + c v_k
// (a short computation shows <X, X> = 0 exactly on the circumcircle). Geodesics are straight
// lines in these projective coordinates, so each input edge is traced through the final
// triangulation by unfolding neighbouring triangles (a linear change of basis per crossed edge,
// closed form in the Penner coordinates of the quad). The start direction of an input edge at
// its vertex is found from horocyclic positions carried through the flips.
#pragma once

#include <cstdint>
#include <vector>

#include "conformal/intrinsic_triangulation.h"

namespace conformesh::conformal {

//! Where a planar point lands on the input surface.
struct PullbackPoint {
  uint32_t face = 0;             //!< input triangle index
  double bary[3] = {0, 0, 0};    //!< barycentric coordinates in that triangle (>= 0, sum 1)
  double position[3] = {0, 0, 0};  //!< the 3D point: bary-weighted input vertices
  //! How far inside the chosen input triangle the point was before clamping (min barycentric
  //! coordinate, normalized; >= 0 inside, slightly negative only from round-off).
  double margin = 0.0;
  int layoutFace = -1;           //!< face of the final intrinsic triangulation containing (x, y)
};

//! Overlay of a source triangulation traced in a target one (same vertices): for every target
//! face, the source faces overlapping it and the change of coordinates into each of them.
//! Hyperbolic: decorated Penner coordinates, traced through Ptolemy flips (the map is
//! projective per cell). Euclidean: the same PL metric, traced through Euclidean flips (the map
//! is affine per cell).
enum class OverlayGeometry { Hyperbolic, Euclidean };

struct OverlayMap {
  std::vector<int> candStart;    //!< per target face, into candFace / candInv
  std::vector<int> candFace;     //!< source face
  std::vector<double> candInv;   //!< 9 per candidate: target-face coords -> source-face coords
  size_t crossings = 0;
  //! Coordinates X (3, in target face t's basis, any positive scale) -> the source face
  //! containing the point and its normalized coordinates there (>= 0, sum 1). margin: the
  //! min normalized coordinate before clamping.
  bool map(int t, const double X[3], int& face, double bary[3], double& margin) const;
};

//! Trace the edges of `src` through `dst` (dst was obtained from src by flips of the given
//! geometry, with positions carried through the flips). Throws conformesh::Error (stage
//! Flatten): NumericalFailure when an edge cannot be traced, TooLarge above the size cap.
OverlayMap buildOverlayMap(const IntrinsicTriangulation& src, const IntrinsicTriangulation& dst, OverlayGeometry geometry);

//! Pull-back from the flattened domain to the input surface, composed of two overlays:
//! final triangulation -> intrinsic Delaunay triangulation of the input (hyperbolic,
//! projective cells) -> input triangulation (Euclidean, affine cells). Immutable; copyable.
class Pullback {
 public:
  //! Map the planar point (x, y) of the flattened domain to the input surface. Returns false
  //! when the point is outside the domain (farther than `tolerance` times the domain diameter).
  bool locate(double x, double y, PullbackPoint& out, double tolerance = 1e-9) const;

  size_t crossings() const { return finalToDelaunay_.crossings + delaunayToInput_.crossings; }
  bool empty() const { return fTri_.empty(); }

  //! Assemble (used by flatten()). xy: layout of the final triangulation; u: its scale factors.
  Pullback(std::vector<double> inputPositions, std::vector<int> inputTriangles, std::vector<double> xy,
           std::vector<int> finalTriangles, std::vector<double> u, OverlayMap finalToDelaunay, OverlayMap delaunayToInput);
  Pullback() = default;

 private:
  std::vector<double> inPos_;      // 3 nV input positions
  std::vector<int> inTri_;         // 3 nF input triangles
  std::vector<double> xy_;         // 2 nV layout positions
  std::vector<int> fTri_;          // 3 nFinal final triangles
  std::vector<double> u_;          // per vertex log scale factor
  OverlayMap finalToDelaunay_, delaunayToInput_;
  double lo_[2] = {0, 0}, cell_ = 1, diam_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<int> gridStart_, gridFaces_;
};

}  // namespace conformesh::conformal
