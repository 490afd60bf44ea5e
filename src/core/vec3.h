// conformesh — the library's one 3D point and vector: three doubles and the arithmetic the stages
// use. Eigen is for the solvers' linear algebra only (conformal/flow_solve), never for points.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace conformesh {

//! A point or a vector in 3D. Each operation evaluates in the order written (x, y, z; sums left
//! to right): the outputs' bits depend on that order (docs/ARCHITECTURE.md, "Determinism").
struct Vec3 {
  double x = 0, y = 0, z = 0;
  //! Coordinate k (0: x, 1: y, 2: z).
  double operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
  double& operator[](int k) { return k == 0 ? x : (k == 1 ? y : z); }
  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
  bool operator!=(const Vec3& o) const { return !(*this == o); }
};

//! (a.x b.x + a.y b.y) + a.z b.z.
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
//! Point i of a flat array of 3·n coordinates (MeshBuffers::positions and the like).
inline Vec3 vec3At(const std::vector<double>& xyz, size_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
//! Euclidean length (sqrt is correctly rounded on every target).
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

}  // namespace conformesh
