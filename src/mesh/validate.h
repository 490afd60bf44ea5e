// conformesh — validation and repair of an input triangle mesh (pipeline stage "validate").
//
// validate() turns flat arrays into a HalfedgeMesh, repairing what can be repaired and failing
// with a clear status on what cannot. The policy (defaults; options change some of it):
//
//   status                   | policy
//   -------------------------|----------------------------------------------------------------
//   EmptyMesh                | fatal: no vertices, no triangles, or every triangle degenerate
//   TooLarge                 | fatal: nV > maxVertices or nF > maxTriangles
//   IndexOutOfRange          | fatal: the first offending triangle and index are named
//   NonFiniteCoordinate      | fatal: any vertex (used or not) with a NaN/inf coordinate, named
//   DegenerateFace           | repaired: triangles repeating a vertex index are dropped; triangles
//                            | with exactly collinear corners (zero area, decided exactly — no
//                            | tolerance, see exactlyCollinear) are dropped (dropZeroAreaFaces).
//                            | Warning with the count. Dropping a zero-area triangle that has
//                            | neighbours leaves a slit (a boundary) where it was.
//   duplicate triangles      | fatal as NonManifoldEdge (both triangles named); dropped with a
//                            | DegenerateFace warning when dropDuplicateFaces
//   NonManifoldEdge          | fatal: an edge in more than two triangles (vertices, triangles named)
//   InconsistentOrientation  | repaired: per connected component, breadth-first search over
//                            | manifold edges, the orientation of the majority of the component's
//                            | triangles kept, the others reversed; warning with the count.
//                            | Fatal if fixOrientation is false.
//   non-orientable component | fatal as InvalidTopology (Möbius strip, Klein bottle)
//   NonManifoldVertex        | fatal: a vertex whose triangles form several fans (bow-tie), named;
//                            | with splitNonManifoldVertices each extra fan gets a copy of the
//                            | vertex (appended after the other vertices), warning with the count
//   unreferenced vertices    | removed (vertex order otherwise kept), a note with the count
//                            | (warning code Ok); vertexToInput / inputToVertex map them
//
// Every thrown Error has stage Validate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"
#include "core/status.h"
#include "mesh/halfedge_mesh.h"
#include "mesh/mesh_geometry.h"

namespace conformesh {

struct ValidateOptions {
  //! Inputs with more vertices / triangles fail with TooLarge. The defaults (16 M each) keep a
  //! mesh and its halfedge structure well inside the 4 GB a WASM module can use; native callers
  //! may raise them (hard limit: 32-bit handles, about 357 M triangles).
  size_t maxVertices = size_t(16) << 20;
  size_t maxTriangles = size_t(16) << 20;
  bool dropZeroAreaFaces = true;         //!< false: keep them (only triangles repeating a vertex go)
  bool dropDuplicateFaces = false;       //!< true: drop later copies instead of failing
  bool fixOrientation = true;            //!< false: InconsistentOrientation is fatal
  bool splitNonManifoldVertices = false;  //!< true: give each extra fan of a bow-tie its own vertex
};

//! A non-fatal finding. code: the status it stands for (DegenerateFace, InconsistentOrientation,
//! NonManifoldVertex when split, ...), or Ok for a note that changed nothing geometric (removed
//! unreferenced vertices). count: how many elements it concerns.
struct ValidationWarning {
  Code code = Code::Ok;
  size_t count = 0;
  std::string message;
};

struct ValidationReport {
  size_t inputVertices = 0, inputTriangles = 0;
  size_t degenerateFaces = 0;   //!< dropped: repeated vertex index or zero area
  size_t zeroAreaFaces = 0;     //!< of those (or kept, when !dropZeroAreaFaces): exactly collinear
  size_t duplicateFaces = 0;    //!< dropped (only with dropDuplicateFaces)
  size_t flippedFaces = 0;      //!< reversed to make the orientation consistent
  size_t splitVertices = 0;     //!< vertex copies added at bow-ties
  size_t removedVertices = 0;   //!< unreferenced input vertices removed
  std::vector<ValidationWarning> warnings;
};

//! The repaired mesh. buffers and mesh describe the same triangles: face f of `mesh` is
//! triangle f of `buffers`, vertex v is vertex v (see halfedge_mesh.h).
struct ValidatedMesh {
  MeshBuffers buffers;               //!< repaired arrays (uvs carried along when given)
  HalfedgeMesh mesh;
  VertexData<Vec3> positions;        //!< buffers.positions as VertexData
  std::vector<uint32_t> vertexToInput;  //!< output vertex -> input vertex
  std::vector<uint32_t> inputToVertex;  //!< input vertex -> output vertex (0xffffffff: removed;
                                        //!< a split vertex maps to its first copy)
  std::vector<uint32_t> faceToInput;    //!< output triangle -> input triangle
  ValidationReport report;
};

//! Validate and repair `input` as described above.
//! \throw Error (stage Validate) with the fatal statuses listed in the table above, or
//!   InvalidArgument when the array lengths are not multiples of 3 (uvs: 0 or 2·nV).
ValidatedMesh validate(const MeshBuffers& input, const ValidateOptions& options = {});

}  // namespace conformesh
