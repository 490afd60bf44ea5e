// conformesh — positions beside a HalfedgeMesh, and the few geometric primitives the mesh
// queries need (face normal, edge vector, exact collinearity).
#pragma once

#include "core/mesh_buffers.h"
#include "core/vec3.h"
#include "mesh/halfedge_mesh.h"

namespace conformesh {

//! Vertex positions of `buffers` as VertexData (nV entries, same order).
VertexData<Vec3> vertexPositions(const MeshBuffers& buffers);

//! (p1 - p0) × (p2 - p0) for face f: twice its area times its unit normal (counter-clockwise
//! seen from the side it points to). Zero for a degenerate face.
Vec3 faceAreaNormal(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos, FaceId f);

//! tip - tail of h.
inline Vec3 edgeVector(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos, HalfedgeId h) {
  return pos[mesh.tip(h)] - pos[mesh.tail(h)];
}

//! Exactly whether the three points are collinear (the triangle has zero area), decided without
//! rounding error: each of the three coordinate-plane orientations is tested by a floating-point
//! filter and, when the filter cannot decide, by exact expansion arithmetic (Shewchuk 1997,
//! "Adaptive precision floating-point arithmetic and fast robust geometric predicates": Two-Sum,
//! Two-Product by Dekker splitting, Grow-Expansion). Exact for finite coordinates whose pairwise
//! products neither overflow nor fall below about 1e-290 in magnitude (the products' rounding
//! errors must be representable).
bool exactlyCollinear(const double* a, const double* b, const double* c);

}  // namespace conformesh
