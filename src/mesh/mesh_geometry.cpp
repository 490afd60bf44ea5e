#include "mesh/mesh_geometry.h"

#include <cmath>

namespace conformesh {

VertexData<Vec3> vertexPositions(const MeshBuffers& buffers) {
  const size_t n = buffers.vertexCount();
  VertexData<Vec3> p(n, Vec3::Zero());
  for (size_t i = 0; i < n; ++i)
    p.data()[i] = Vec3(buffers.positions[3 * i], buffers.positions[3 * i + 1], buffers.positions[3 * i + 2]);
  return p;
}

Vec3 faceAreaNormal(const HalfedgeMesh& mesh, const VertexData<Vec3>& pos, FaceId f) {
  auto v = mesh.faceVertices(f);
  return (pos[v[1]] - pos[v[0]]).cross(pos[v[2]] - pos[v[0]]);
}

namespace {
// Shewchuk 1997: error-free transformations. Written one operation per statement so that no
// compiler contracts them into fused multiply-adds.
inline void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  double bv = x - a;
  double av = x - bv;
  double br = b - bv;
  double ar = a - av;
  y = ar + br;
}

inline void split(double a, double& hi, double& lo) {
  const double splitter = 134217729.0;  // 2^27 + 1
  double c = splitter * a;
  double big = c - a;
  hi = c - big;
  lo = a - hi;
}

inline void twoProduct(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  double p1 = ahi * bhi;
  double e1 = x - p1;
  double p2 = alo * bhi;
  double e2 = e1 - p2;
  double p3 = ahi * blo;
  double e3 = e2 - p3;
  double p4 = alo * blo;
  y = p4 - e3;
}

// Exact test: (bx-ax)(cy-ay) - (by-ay)(cx-ax) == 0, expanded into six products
// ax·by − ax·cy − ay·bx + ay·cx + bx·cy − by·cx.
bool orient2dIsZero(double ax, double ay, double bx, double by, double cx, double cy) {
  const double detLeft = (bx - ax) * (cy - ay);
  const double detRight = (by - ay) * (cx - ax);
  const double det = detLeft - detRight;
  const double eps = std::ldexp(1.0, -53);
  const double bound = (3.0 * eps + 16.0 * eps * eps) * (std::fabs(detLeft) + std::fabs(detRight));
  if (std::fabs(det) > bound) return false;
  const double terms[6][2] = {{ax, by}, {-ax, cy}, {-ay, bx}, {ay, cx}, {bx, cy}, {-by, cx}};
  double e[12];
  int n = 0;
  for (const auto& t : terms) {
    double x, y;
    twoProduct(t[0], t[1], x, y);
    for (double b : {y, x}) {  // Grow-Expansion: add b to the expansion e[0..n)
      double q = b;
      for (int i = 0; i < n; ++i) {
        double s, h;
        twoSum(q, e[i], s, h);
        e[i] = h;
        q = s;
      }
      e[n++] = q;
    }
  }
  // A nonoverlapping expansion sums to zero exactly when every component is zero.
  for (int i = 0; i < n; ++i)
    if (e[i] != 0.0) return false;
  return true;
}
}  // namespace

bool exactlyCollinear(const double* a, const double* b, const double* c) {
  return orient2dIsZero(a[0], a[1], b[0], b[1], c[0], c[1]) &&
         orient2dIsZero(a[1], a[2], b[1], b[2], c[1], c[2]) &&
         orient2dIsZero(a[2], a[0], b[2], b[0], c[2], c[0]);
}

}  // namespace conformesh
