// conformesh — topology queries: connected components, boundary loops, Euler characteristic,
// genus, dihedral angles; and meshInfo(), the report behind `conformesh info`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "mesh/halfedge_mesh.h"
#include "mesh/mesh_geometry.h"
#include "mesh/validate.h"

namespace conformesh {

//! Connected components of the faces (faces sharing an edge are connected; in a HalfedgeMesh
//! vertices are manifold, so this equals connection through shared vertices).
struct Components {
  size_t count = 0;
  FaceData<uint32_t> faceComponent;    //!< 0..count-1, numbered by lowest face
  VertexData<uint32_t> vertexComponent;  //!< the component of its faces; 0xffffffff if isolated
};
Components connectedComponents(const HalfedgeMesh& mesh);

//! Boundary loops, each as its boundary halfedges in next() order (clockwise around the hole
//! seen from outside; the loop's vertices are their tails). Loops are ordered by their lowest
//! halfedge index, and each loop starts at its lowest halfedge. Empty for a closed mesh.
std::vector<std::vector<HalfedgeId>> boundaryLoops(const HalfedgeMesh& mesh);

//! χ = V − E + F over the surface (isolated vertices are not counted).
long eulerCharacteristic(const HalfedgeMesh& mesh);

//! Total genus Σ g_i over the components, from χ = Σ (2 − 2g_i − b_i):
//! g = (2·C − χ − b) / 2, with C components and b boundary loops. Always an integer for a
//! HalfedgeMesh (an oriented manifold).
long genus(const HalfedgeMesh& mesh);

//! Signed dihedral angle of every edge, radians in [−π, π]: the angle between the normals of
//! its two faces, positive where the surface is convex (bends away from the normals' side), negative
//! where concave; 0 on boundary edges and where a face has zero area. A cube edge: +π/2.
EdgeData<double> dihedralAngles(const HalfedgeMesh& mesh, const VertexData<Vec3>& positions);

//! Interior edges whose |dihedral angle| exceeds `thresholdRadians` (1), others 0.
EdgeData<uint8_t> sharpEdges(const HalfedgeMesh& mesh, const VertexData<Vec3>& positions, double thresholdRadians);

//! The report of `conformesh info`. Unlike validate(), it never fails on non-manifold or badly
//! oriented input: it counts what it finds and lists it as warnings.
//! Counting rules: degenerate triangles (a repeated vertex index, or exactly zero area) are
//! counted in degenerateFaces and left out of everything else; vertices = vertices used by the
//! other triangles; euler = V − E + F from those counts; components = sets of vertices connected
//! through triangles; boundaryLoops = cycle rank of the graph of boundary edges (edges of exactly
//! one triangle), E_b − V_b + C_b, which is the number of boundary loops on a manifold mesh;
//! genus = (2·components − euler − boundaryLoops) / 2, which may be fractional or negative when
//! the mesh is not a manifold.
struct MeshInfo {
  size_t vertices = 0, faces = 0, edges = 0;
  size_t components = 0, boundaryLoops = 0;
  long euler = 0;
  double genus = 0;
  size_t nonManifoldEdges = 0;     //!< edges of more than two triangles
  size_t nonManifoldVertices = 0;  //!< bow-tie vertices (through manifold edges)
  size_t degenerateFaces = 0;
  size_t duplicateFaces = 0;
  size_t inconsistentFaces = 0;    //!< triangles validate() would reverse
  std::vector<ValidationWarning> warnings;
};

//! \throw Error (stage Validate) for the problems that leave nothing to count: InvalidArgument
//!   (array lengths), EmptyMesh, TooLarge (options' limits), IndexOutOfRange, NonFiniteCoordinate.
MeshInfo meshInfo(const MeshBuffers& mesh, const ValidateOptions& limits = {});

}  // namespace conformesh
