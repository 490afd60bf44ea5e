// conformesh — preconditioning of the input tessellation before segmentation (stage validate).
//
// CAD tessellations are fans of needle triangles whose edges run across whole faces. Cuts and
// patch splits follow input edges, so on such a mesh a cut is a sawtooth of edges as long as the
// face: its flattened image has teeth (spikes) that no planar refinement can mesh well, and the
// refinements on its two sides keep splitting each other's segments near them. Two operations
// that keep the surface exactly as it is fix that:
//   * split every edge longer than maxEdgeLength at its midpoint, longest first (the new vertex
//     lies on the edge, so on the surface; a feature edge gives two feature edges);
//   * Delaunay flips (Lawson) of interior edges whose two triangles are coplanar (within
//     coplanarTolerance; a flat face of a CAD part, or a planar quad of a cylinder strip): the
//     flipped pair covers the same piece of plane.
// Sharp edges (not coplanar), boundary edges and protected (user feature) edges never flip.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh {

struct PreconditionOptions {
  //! Edges longer than this are split (<= 0: no splits).
  double maxEdgeLength = 0.0;
  //! Two triangles are coplanar when 1 − n0·n1 is below this (unit normals): 1e-12 is an angle
  //! of about 1.4e-6 rad.
  double coplanarTolerance = 1e-12;
  //! Per input triangle: 1 where the mesh may be changed (empty: everywhere). An edge is split
  //! or flipped only when a triangle on it is marked; triangles made from a marked one are
  //! marked.
  std::vector<uint8_t> faceMask;
  //! Hard cap on the vertices the splits may add; when reached, splitting stops (reported in
  //! Preconditioned::capped).
  size_t maxNewVertices = 1000000;
};

struct Preconditioned {
  MeshBuffers mesh;
  //! Per vertex of `mesh`: the input vertex it is (the first input.vertexCount() vertices are
  //! the input's, in order), or for a split vertex the two vertices of the edge it halves.
  std::vector<std::array<uint32_t, 2>> parents;
  //! Per triangle of `mesh`: the input triangle it lies in (after a flip of a coplanar pair,
  //! one of the two coplanar input triangles it overlaps).
  std::vector<uint32_t> faceOrigin;
  //! The protected edges given, as edges of `mesh` (a split protected edge gives both halves).
  std::vector<std::array<uint32_t, 2>> protectedEdges;
  size_t splits = 0, flips = 0;
  bool capped = false;  //!< maxNewVertices stopped the splits
};

//! Precondition a valid (manifold, consistently oriented) mesh. `protectedEdges` are vertex
//! pairs that must stay edges (user feature edges); pairs that are not edges are ignored.
Preconditioned precondition(const MeshBuffers& input, const std::vector<std::array<uint32_t, 2>>& protectedEdges,
                            const PreconditionOptions& options);

}  // namespace conformesh
