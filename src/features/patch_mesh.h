// conformesh — a patch (a set of input faces) as a sub-mesh of its own, cut open along curves.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "features/edge_graph.h"

namespace conformesh::features {

//! A patch extracted as a mesh. Input vertices are split into "wedges": one sub-mesh vertex per
//! fan of patch faces around the vertex that is connected without crossing a curve edge. So a
//! curve with the patch on both sides (a seam) becomes two boundary edges, and a patch touching
//! itself at a vertex becomes manifold there.
//!   mesh          positions (3D, copied from the input) and triangles over sub-mesh vertices,
//!                 same orientation as the input
//!   faceInput     input face of each sub-mesh triangle
//!   vertexInput   input vertex of each sub-mesh vertex
//!   boundaryLoops each loop a sequence of sub-mesh boundary halfedges, as (face, corner):
//!                 halfedge from corner to corner+1 of sub triangle `face`, the patch on its left
struct PatchMesh {
  MeshBuffers mesh;
  std::vector<uint32_t> faceInput;
  std::vector<uint32_t> vertexInput;
  struct BoundaryHalfedge {
    uint32_t face;   //!< sub-mesh triangle
    uint8_t corner;  //!< the halfedge runs from corner to (corner+1)%3
  };
  std::vector<std::vector<BoundaryHalfedge>> boundaryLoops;
  int eulerCharacteristic = 0;

  //! χ = 1 and exactly one boundary loop: a topological disk.
  //! True when two sub-mesh vertices are the same input vertex: the patch touches itself at a
  //! vertex (a pinch), so its boundary is not a simple curve on the surface.
  bool pinched = false;
  //! A disk whose boundary is a simple curve on the surface (no pinch: a flattening that keeps
  //! lengths, as the free boundary does on a developable patch, would make it touch itself).
  bool isDisk() const { return eulerCharacteristic == 1 && boundaryLoops.size() == 1 && !pinched; }
  //! Genus from χ = 2 − 2g − b.
  int genus() const { return (2 - eulerCharacteristic - int(boundaryLoops.size())) / 2; }
};

//! Extract the faces `faces` (each face once) as a PatchMesh. `isCurve[e]` marks input edges the
//! patch is cut open along. Throws Error(InternalError) when the boundary cannot be traced
//! (only possible for a non-manifold input, which buildEdgeGraph rejects).
PatchMesh extractPatch(const EdgeGraph& g, const std::vector<uint8_t>& isCurve,
                       const std::vector<uint32_t>& faces, bool traceLoops = true);

//! extractPatch(g, isCurve, faces, false).isDisk() without building the patch: for the checks a
//! cut or a join makes of the patches it would leave. O(faces).
bool isDiskRegion(const EdgeGraph& g, const std::vector<uint8_t>& isCurve, const std::vector<uint32_t>& faces);

}  // namespace conformesh::features
