#include "mesh/mesh_geometry.h"

#include "planar/predicates.h"

#include <cmath>

namespace conformesh {

VertexData<Vec3> vertexPositions(const MeshBuffers& buffers) {
  const size_t n = buffers.vertexCount();
  VertexData<Vec3> p(n, Vec3{});
  for (size_t i = 0; i < n; ++i)
    p.data()[i] = vec3At(buffers.positions, i);
  return p;
}

Vec3 faceAreaNormal(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos, FaceId f) {
  auto v = mesh.faceVertices(f);
  return cross(pos[v[1]] - pos[v[0]], pos[v[2]] - pos[v[0]]);
}

// Three points are collinear exactly when their projections onto the three coordinate planes are
// all collinear; each projection is decided by the exact planar orient2d (Shewchuk 1997).
bool exactlyCollinear(const double* a, const double* b, const double* c) {
  if (planar::orient2d(a, b, c) != 0.0) return false;              // (x, y)
  if (planar::orient2d(a + 1, b + 1, c + 1) != 0.0) return false;  // (y, z)
  const double az[2] = {a[2], a[0]}, bz[2] = {b[2], b[0]}, cz[2] = {c[2], c[0]};
  return planar::orient2d(az, bz, cz) == 0.0;                       // (z, x)
}

}  // namespace conformesh
