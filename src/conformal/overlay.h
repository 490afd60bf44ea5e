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
  //! Hinted locate only: faces the walk crossed to reach layoutFace; -1 when the grid search
  //! decided (no hint, or the walk could not be sure).
  int walkSteps = -1;
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

  //! The same, starting from a hint: hintFace is a face of the final triangulation near (x, y)
  //! (e.g. PullbackPoint::layoutFace of an earlier nearby point; -1: none). A visibility walk
  //! from the hint (Devillers–Pion–Teillaud 2002, "Walking in a triangulation"; it terminates on
  //! a Delaunay triangulation, Edelsbrunner 1990, and the final triangulation is Delaunay in the
  //! layout) ends in the face containing the point; where the point is not clearly inside a
  //! face (near an edge, off the domain, a walk that hits the boundary or its step cap), the
  //! grid search above decides. On an embedded layout (flatten(): invertedTriangles == 0 and
  //! boundaryCrossings == 0) the result is bit-identical to locate(x, y, out, tolerance).
  bool locate(double x, double y, int hintFace, PullbackPoint& out, double tolerance = 1e-9) const;

  //! The face of the final triangulation containing (x, y) and the point's barycentric
  //! coordinates in it (clamped to >= 0, sum 1), not mapped to the input: for fields given per
  //! vertex, which the final triangulation shares with the input. face: in, a hint as above (-1:
  //! none); out, the face found. vertices: its three vertices. False off the domain.
  bool locateLayout(double x, double y, int& face, int vertices[3], double bary[3], double tolerance = 1e-9) const;

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
  OverlayMap finalToDelaunay_, delaunayToInput_;
  // Twice the signed areas of final face t (`area`) and of the triangles (x, y) makes with its
  // edge opposite each corner (w): the barycentrics times the area, without a division.
  void faceProducts(int t, double x, double y, double w[3], double& area) const;
  // The barycentrics from those products (area > 0) and the grid search's score (min coordinate
  // times sqrt(area) / diam).
  double coordsFrom(const double w[3], double area, double B[3]) const;
  // Barycentrics of (x, y) in final face t and the grid search's score; false when t has no
  // positive area.
  bool faceCoords(int t, double x, double y, double B[3], double& score) const;
  // From final face t and the (unclamped) barycentrics of the point there to the input surface.
  bool finish(int t, const double B[3], PullbackPoint& out) const;
  // The face whose coordinates of (x, y) have the largest score, in the point's grid cell and
  // the ring around it; -1 when the best score is below -tolerance (off the domain).
  int gridSearch(double x, double y, double B[3], double tolerance) const;
  // Visibility walk from hintFace; the face when the point is surely inside it, else -1.
  int walk(double x, double y, int hintFace, double B[3], int& steps) const;

  std::vector<int> fNbr_;          // 3 nFinal: the face across the edge opposite corner k, -1 none
  std::vector<double> fScale_;     // 3 nFinal: exp(u - max u over the face) per corner
  double lo_[2] = {0, 0}, cell_ = 1, diam_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<int> gridStart_, gridFaces_;
};

}  // namespace conformesh::conformal
