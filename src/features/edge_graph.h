// conformesh — the edge/face adjacency the segmentation stage works on.
//
// A compact, index-based view of a manifold triangle mesh: unique undirected edges, the (at most
// two) faces on each edge, the three edges of each face and the edges around each vertex. It is
// built straight from MeshBuffers so the features stage does not depend on a particular halfedge
// implementation.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"
#include "core/detmath.h"
#include "core/vec3.h"

namespace conformesh::features {

constexpr uint32_t kNone = 0xffffffffu;

//! Angle in radians between two vectors (0 for a zero vector).
inline double angleBetween(const Vec3& a, const Vec3& b) {
  double c = norm(cross(a, b)), d = dot(a, b);
  return (c == 0 && d == 0) ? 0.0 : dmath::atan2(c, d);
}

//! Edge/face adjacency of a triangle mesh.
//!   edgeVerts[e]  the two vertex indices of edge e, smaller first
//!   edgeFaces[e]  the faces on edge e (kNone for a missing side); edgeFaces[e][0] traverses the
//!                 edge as edgeVerts[e][0] -> edgeVerts[e][1] when orientation is consistent
//!   faceEdges[f]  faceEdges[f][i] is the edge from corner i to corner (i+1)%3 of face f
//!   vertexEdges   CSR: edges around vertex v are vertexEdgeIds[vertexEdgeStart[v] .. [v+1])
struct EdgeGraph {
  uint32_t vertexCount = 0;
  uint32_t faceCount = 0;
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> faces;
  std::vector<std::array<uint32_t, 2>> edgeVerts;
  std::vector<std::array<uint32_t, 2>> edgeFaces;
  std::vector<std::array<uint32_t, 3>> faceEdges;
  std::vector<uint32_t> vertexEdgeStart;
  std::vector<uint32_t> vertexEdgeIds;

  uint32_t edgeCount() const { return uint32_t(edgeVerts.size()); }
  bool isBoundary(uint32_t e) const { return edgeFaces[e][1] == kNone; }
  uint32_t otherVertex(uint32_t e, uint32_t v) const {
    return edgeVerts[e][0] == v ? edgeVerts[e][1] : edgeVerts[e][0];
  }
  double edgeLength(uint32_t e) const { return norm(positions[edgeVerts[e][1]] - positions[edgeVerts[e][0]]); }
  //! Unit normal of face f (zero vector for a zero-area face).
  Vec3 faceNormal(uint32_t f) const;
  double faceArea(uint32_t f) const;
  Vec3 faceCentroid(uint32_t f) const;
  //! Interior angle (radians) of face f at its corner i.
  double cornerAngle(uint32_t f, int i) const;
  //! The edge between vertices a and b, or kNone.
  uint32_t findEdge(uint32_t a, uint32_t b) const;
};

//! Build the adjacency. Throws Error(NonManifoldEdge, Segment) when an edge has more than two
//! faces, Error(IndexOutOfRange) for bad indices, Error(EmptyMesh) for an empty mesh.
EdgeGraph buildEdgeGraph(const MeshBuffers& mesh);

}  // namespace conformesh::features
