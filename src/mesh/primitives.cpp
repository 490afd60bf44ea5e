#include "mesh/primitives.h"
#include "core/constants.h"
#include "core/detmath.h"
#include "core/vec3.h"

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>

namespace conformesh {

namespace {

void checkArg(bool ok, const std::string& what) {
  if (!ok) fail(Code::InvalidArgument, Stage::Api, what);
}

uint32_t addVertex(MeshBuffers& m, double x, double y, double z) {
  m.positions.insert(m.positions.end(), {x, y, z});
  return uint32_t(m.positions.size() / 3 - 1);
}

void addTriangle(MeshBuffers& m, uint32_t a, uint32_t b, uint32_t c) { m.triangles.insert(m.triangles.end(), {a, b, c}); }

// Quad a b c d (counter-clockwise) as two triangles.
void addQuad(MeshBuffers& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  addTriangle(m, a, b, c);
  addTriangle(m, a, c, d);
}

// A closed grid: vertex (i, j) = index i*nj + j, periodic in both directions; position given.
template <class F>
MeshBuffers periodicGrid(int ni, int nj, F position) {
  MeshBuffers m;
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j) {
      const Vec3 p = position(i, j);
      addVertex(m, p[0], p[1], p[2]);
    }
  auto id = [&](int i, int j) { return uint32_t((i % ni) * nj + (j % nj)); };
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j) addQuad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  return m;
}
}  // namespace

MeshBuffers makeIcosphere(int s) {
  checkArg(s >= 0 && s <= 8, "icosphere subdivisions must be in [0, 8]");
  MeshBuffers m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : base) {
    double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    addVertex(m, p[0] / n, p[1] / n, p[2] / n);
  }
  m.triangles = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int level = 0; level < s; ++level) {
    std::unordered_map<uint64_t, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      double p[3], n = 0;
      for (int k = 0; k < 3; ++k) {
        p[k] = m.positions[3 * a + k] + m.positions[3 * b + k];
        n += p[k] * p[k];
      }
      n = std::sqrt(n);
      uint32_t v = addVertex(m, p[0] / n, p[1] / n, p[2] / n);
      mid.emplace(key, v);
      return v;
    };
    std::vector<uint32_t> old;
    old.swap(m.triangles);
    for (size_t f = 0; f < old.size() / 3; ++f) {
      uint32_t a = old[3 * f], b = old[3 * f + 1], c = old[3 * f + 2];
      uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      addTriangle(m, a, ab, ca);
      addTriangle(m, b, bc, ab);
      addTriangle(m, c, ca, bc);
      addTriangle(m, ab, bc, ca);
    }
  }
  return m;
}

MeshBuffers makeTorus(int nu, int nv, double R, double r) {
  checkArg(nu >= 3 && nv >= 3 && R > r && r > 0, "torus needs segments >= 3 and R > r > 0");
  return periodicGrid(nu, nv, [&](int i, int j) {
    double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
    return Vec3{(R + r * dmath::cos(v)) * dmath::cos(u), (R + r * dmath::cos(v)) * dmath::sin(u), r * dmath::sin(v)};
  });
}

MeshBuffers makeDisk(int rings, int sectors, double radius) {
  checkArg(rings >= 1 && sectors >= 3 && radius > 0, "disk needs rings >= 1, sectors >= 3, radius > 0");
  MeshBuffers m;
  addVertex(m, 0, 0, 0);
  for (int k = 1; k <= rings; ++k)
    for (int i = 0; i < sectors; ++i) {
      double a = 2 * kPi * i / sectors, rr = radius * k / rings;
      addVertex(m, rr * dmath::cos(a), rr * dmath::sin(a), 0);
    }
  auto id = [&](int k, int i) { return k == 0 ? 0u : uint32_t(1 + (k - 1) * sectors + i % sectors); };
  for (int i = 0; i < sectors; ++i) addTriangle(m, 0, id(1, i), id(1, i + 1));
  for (int k = 1; k < rings; ++k)
    for (int i = 0; i < sectors; ++i) addQuad(m, id(k, i), id(k + 1, i), id(k + 1, i + 1), id(k, i + 1));
  return m;
}

MeshBuffers makeAnnulus(int rings, int sectors, double r0, double r1) {
  checkArg(rings >= 1 && sectors >= 3 && r1 > r0 && r0 > 0, "annulus needs rings >= 1, sectors >= 3, 0 < r0 < r1");
  MeshBuffers m;
  for (int k = 0; k <= rings; ++k)
    for (int i = 0; i < sectors; ++i) {
      double a = 2 * kPi * i / sectors, rr = r0 + (r1 - r0) * k / rings;
      addVertex(m, rr * dmath::cos(a), rr * dmath::sin(a), 0);
    }
  auto id = [&](int k, int i) { return uint32_t(k * sectors + i % sectors); };
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < sectors; ++i) addQuad(m, id(k, i), id(k + 1, i), id(k + 1, i + 1), id(k, i + 1));
  return m;
}

MeshBuffers makeCube(int n, double h) {
  checkArg(n >= 1 && h > 0, "cube needs n >= 1 and halfSize > 0");
  MeshBuffers m;
  // welds the grid vertices shared by faces (points ordered by x, then y, then z)
  auto lexLess = [](const Vec3& a, const Vec3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::map<Vec3, uint32_t, decltype(lexLess)> index(lexLess);
  auto coord = [&](int i) { return -h + 2.0 * h * i / n; };
  auto vertex = [&](const Vec3& p) {
    auto it = index.find(p);
    if (it != index.end()) return it->second;
    uint32_t v = addVertex(m, p[0], p[1], p[2]);
    index.emplace(p, v);
    return v;
  };
  // Face with normal sign·e_axis; (u, w) axes chosen so that e_u × e_w = sign·e_axis.
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      int u = (axis + 1) % 3, w = (axis + 2) % 3;
      if (sign < 0) std::swap(u, w);
      auto point = [&](int i, int j) {
        Vec3 p;
        p[axis] = sign * h;
        p[u] = coord(i);
        p[w] = coord(j);
        return vertex(p);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) addQuad(m, point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1));
    }
  return m;
}

MeshBuffers makeBoxWithHole(int n, double outer, double hole, double height) {
  checkArg(n >= 1 && outer > hole && hole > 0 && height > 0, "box with hole needs n >= 1, outer > hole > 0, height > 0");
  // A "square torus": the path is the boundary of the unit square (counter-clockwise, n segments
  // per side, scaled by the radial coordinate s), the profile a rectangle in (s, z) walked
  // outer wall up, top inwards, hole wall down, bottom outwards.
  auto squarePoint = [&](int k) {
    static const double corners[5][2] = {{1, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    int side = k / n, t = k % n;
    double a = double(t) / n;
    return std::array<double, 2>{corners[side][0] + a * (corners[side + 1][0] - corners[side][0]),
                                 corners[side][1] + a * (corners[side + 1][1] - corners[side][1])};
  };
  auto profilePoint = [&](int k) {
    const double pts[5][2] = {{outer, 0}, {outer, height}, {hole, height}, {hole, 0}, {outer, 0}};
    int side = k / n, t = k % n;
    double a = double(t) / n;
    return std::array<double, 2>{pts[side][0] + a * (pts[side + 1][0] - pts[side][0]),
                                 pts[side][1] + a * (pts[side + 1][1] - pts[side][1])};
  };
  return periodicGrid(4 * n, 4 * n, [&](int i, int j) {
    auto q = squarePoint(i);
    auto p = profilePoint(j);
    return Vec3{p[0] * q[0], p[0] * q[1], p[1]};
  });
}

}  // namespace conformesh
