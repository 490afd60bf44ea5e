// conformesh — the checks shared by validate() and meshInfo() (internal to src/mesh).
//
// Each check analyses and counts; the callers decide what is fatal (validate) and what is only
// reported (meshInfo).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "mesh/edge_groups.h"

namespace conformesh::detail {

constexpr uint32_t kNone = 0xffffffffu;

//! Throws the fatal buffer-level problems, in this order: InvalidArgument (array lengths not
//! multiples of 3, uvs not empty or 2·nV), EmptyMesh (no vertices or no triangles), TooLarge
//! (nV > maxVertices or nF > maxTriangles), IndexOutOfRange (first bad triangle named),
//! NonFiniteCoordinate (first bad vertex named; every vertex is checked, used or not).
void checkBuffers(const MeshBuffers& m, size_t maxVertices, size_t maxTriangles, Stage stage);

//! The triangles left after dropping degenerate ones.
struct FaceFilter {
  std::vector<uint32_t> tris;         //!< kept triangles (3 indices each)
  std::vector<uint32_t> faceToInput;  //!< kept triangle -> input triangle
  size_t repeatedVertex = 0;          //!< dropped: a vertex index appears twice
  size_t zeroArea = 0;                //!< dropped (or only counted): exactly collinear corners
  uint32_t firstDegenerate = kNone;   //!< an input triangle among the above
};
//! Drops triangles that repeat a vertex; with dropZeroArea, also those whose corners are exactly
//! collinear (exactlyCollinear: no tolerance). Pre: checkBuffers passed.
FaceFilter filterDegenerateFaces(const MeshBuffers& m, bool dropZeroArea);

//! Triangles that use the same three vertices as an earlier one (any order or orientation).
struct Duplicates {
  std::vector<uint8_t> isDuplicate;  //!< per triangle: 1 if an earlier triangle has its vertices
  size_t count = 0;
  uint32_t first = kNone, firstOriginal = kNone;  //!< one duplicate and the triangle it repeats
};
Duplicates findDuplicateFaces(const std::vector<uint32_t>& tris);

//! Edge statistics of a triangle list, and each corner's partner across a two-triangle edge.
struct EdgeStats {
  size_t edges = 0, boundaryEdges = 0, nonManifoldEdges = 0;
  uint32_t firstNonManifoldCorner = kNone;  //!< a corner on a non-manifold edge
  uint32_t firstNonManifoldFaces = 0;       //!< how many triangles share that edge
  std::vector<uint32_t> partner;  //!< per corner: the other corner of its edge if exactly 2, else kNone
  std::vector<uint32_t> boundaryCorners;  //!< corners on edges of exactly one triangle
};
EdgeStats edgeStats(const EdgeGroups& groups, const std::vector<uint32_t>& tris);

//! Consistent orientation by breadth-first search over two-triangle edges (components joined only
//! through manifold edges). In each component the orientation of the majority of its triangles is
//! kept (ties: the lowest-numbered triangle's).
struct Orientation {
  std::vector<uint8_t> flip;  //!< per triangle: reverse it
  size_t flipped = 0;
  size_t inconsistentEdges = 0;           //!< edges traversed the same way by both triangles
  size_t nonOrientableComponents = 0;     //!< components that cannot be oriented (Möbius, Klein)
  uint32_t firstNonOrientableFace = kNone;
};
Orientation orientFaces(const std::vector<uint32_t>& tris, const std::vector<uint32_t>& partner);

//! Fans (umbrellas) at each vertex: corners joined across two-triangle edges. A vertex with more
//! than one fan is a bow-tie (non-manifold vertex).
struct Fans {
  std::vector<uint32_t> cornerFan;  //!< per corner: a representative corner of its fan
  size_t bowtieVertices = 0;
  size_t extraFans = 0;  //!< sum over vertices of (fans - 1)
  uint32_t firstBowtie = kNone;
};
Fans vertexFans(size_t vertexCount, const std::vector<uint32_t>& tris, const std::vector<uint32_t>& partner);

//! Union–find over 0..n-1 (path halving).
struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n);
  uint32_t find(uint32_t x);
  bool unite(uint32_t a, uint32_t b);  //!< true if a and b were in different sets
};

}  // namespace conformesh::detail
