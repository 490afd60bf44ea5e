// conformesh — a compact intrinsic triangulation with edge flips (Ptolemy) for the flatten stage.
//
// Halfedge h lives in face h/3; next(h) = 3(h/3) + (h+1)%3. twin(h) = -1 on the boundary.
// Edge lengths are stored as "base" log lengths lam = 2 log l in Penner coordinates: the
// scaled metric for vertex scale factors u is lam~_ij = lam_ij + u_i + u_j, and a flip uses
// the Ptolemy relation l_cd l_ab = l_ac l_bd + l_ad l_bc, which commutes with vertex scaling
// (Gillespie–Springborn–Crane 2021; Springborn 2020 "Ideal hyperbolic polyhedra and discrete
// uniformization"), so flips may be done in base coordinates at any u.
//
// Overlay bookkeeping (for the pull-back): every outgoing halfedge carries its horocyclic
// position at its origin vertex (Penner 1987: the horocycle arc of a decorated ideal triangle
// at vertex i has length l_jk / (l_ij l_ik)), measured counter-clockwise from a reference
// direction; flips keep these positions, so input edges can later be traced in the final
// triangulation. Edges that were never flipped remember their input edge (`origin`).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::conformal {

struct IntrinsicTriangulation {
  int nV = 0, nF = 0, nE = 0;
  std::vector<int> vert;        //!< per halfedge: origin vertex
  std::vector<int> twin;        //!< per halfedge: opposite halfedge, -1 on the boundary
  std::vector<int> edge;        //!< per halfedge: edge index
  std::vector<int> edgeHalf;    //!< per edge: one of its halfedges
  std::vector<double> lambda;   //!< per edge: base log length 2 log l (Penner coordinate)
  std::vector<int> origin;      //!< per edge: input edge index, -1 once flipped
  std::vector<char> locked;     //!< per edge: never flipped (empty: none is locked)
  //! What the per-halfedge positions measure: horocycle arc length (decorated hyperbolic
  //! metric, kept by Ptolemy flips) or angle (Euclidean metric, kept by Euclidean flips).
  enum class PositionKind { Horocyclic, Angular };
  PositionKind positionKind = PositionKind::Horocyclic;
  std::vector<double> horoPos;  //!< per halfedge: position at its origin vertex, counter-clockwise
  std::vector<double> horoTotal;   //!< per vertex: total (interior vertices: the period)
  std::vector<char> boundaryVertex;  //!< per vertex
  std::vector<std::vector<int>> loops;      //!< boundary loops: vertex sequences, domain on the left
  std::vector<std::vector<int>> loopEdges;  //!< loops[k][i] -> loops[k][i+1] edge index
  long long flips = 0;

  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  int tip(int h) const { return vert[next(h)]; }

  //! Scaled log length of the edge of halfedge h.
  double scaledLambda(int h, const std::vector<double>& u) const {
    return lambda[edge[h]] + u[vert[h]] + u[tip(h)];
  }

  //! Flip the interior edge e (Ptolemy). Precondition: canFlip(e).
  void flip(int e);
  //! Flip the interior edge e keeping the Euclidean metric (u = 0): the new length is the
  //! quad's other diagonal. Precondition: canFlip(e) and the quad is convex (true for a
  //! non-Delaunay edge).
  void flipEuclidean(int e);
  //! Size of the corner of g's face at g's origin, in the current position kind.
  double cornerSize(int g) const;
  //! Recompute all positions from scratch in the given kind; boundary vertices start at their
  //! boundary halfedge, interior ones at an arbitrary outgoing halfedge.
  void resetPositions(PositionKind kind);
  //! Declare the current triangulation the reference: origin[e] = e for all edges.
  void resetOrigins();
  //! Flip e, giving the new edge the log length lcd (connectivity and positions only).
  void flipWithLambda(int e, double lcd);
  //! Interior edge whose two sides are different faces.
  bool canFlip(int e) const;
};

//! Build from flat arrays. Validates: indices in range, no repeated vertex in a face, finite
//! coordinates, no zero-length edge or zero-area face, manifold edges with consistent
//! orientation, manifold vertices, one connected component, and a planar domain (genus 0 with
//! at least one boundary loop). Throws conformesh::Error (stage Flatten) otherwise.
IntrinsicTriangulation buildIntrinsicTriangulation(const MeshBuffers& mesh);

}  // namespace conformesh::conformal
