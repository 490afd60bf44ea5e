// Small generated meshes for the features and remesh tests (closed, consistently oriented, outward).
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::testshapes {

struct Builder {
  MeshBuffers m;
  std::map<std::tuple<long long, long long, long long>, uint32_t> index;
  uint32_t vertex(double x, double y, double z) {
    auto key = std::make_tuple(std::llround(x * 1e9), std::llround(y * 1e9), std::llround(z * 1e9));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    uint32_t id = uint32_t(m.positions.size() / 3);
    m.positions.insert(m.positions.end(), {x, y, z});
    index.emplace(key, id);
    return id;
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) { m.triangles.insert(m.triangles.end(), {a, b, c}); }
};

//! Axis-aligned cube [0, s]^3, every face an n × n grid of quads split into two triangles.
inline MeshBuffers cube(int n, double s = 1.0) {
  Builder b;
  // face: origin o, axes u, v with u × v outward
  const double F[6][9] = {{0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 1, 1, 0, 0, 0, 1, 0},
                          {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1, 1, 0, 0},
                          {0, 0, 0, 0, 0, 1, 0, 1, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  for (const auto& f : F) {
    auto P = [&](int i, int j) {
      double a = double(i) / n, c = double(j) / n;
      return b.vertex(s * (f[0] + a * f[3] + c * f[6]), s * (f[1] + a * f[4] + c * f[7]),
                      s * (f[2] + a * f[5] + c * f[8]));
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        uint32_t p00 = P(i, j), p10 = P(i + 1, j), p01 = P(i, j + 1), p11 = P(i + 1, j + 1);
        b.tri(p00, p10, p11);
        b.tri(p00, p11, p01);
      }
  }
  return b.m;
}

//! The box [0, sx] × [0, sy] × [0, sz]: cube(n) scaled along each axis (a thin slab when one side
//! is small: its rim is a strip of creases that close together).
inline MeshBuffers box(int n, double sx, double sy, double sz) {
  MeshBuffers m = cube(n);
  for (size_t i = 0; i < m.positions.size(); i += 3) {
    m.positions[i] *= sx;
    m.positions[i + 1] *= sy;
    m.positions[i + 2] *= sz;
  }
  return m;
}

//! Closed cylinder: radius r, height h, m segments around, k rings along the axis, flat caps
//! made of rings too (c rings from the centre).
inline MeshBuffers cylinder(int m, int k, int c, double r = 0.5, double h = 1.0) {
  Builder b;
  const double pi = 3.14159265358979323846;
  auto side = [&](int i, int j) {
    double a = 2 * pi * (i % m) / m;
    return b.vertex(r * std::cos(a), r * std::sin(a), h * j / k);
  };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < k; ++j) {
      uint32_t p00 = side(i, j), p10 = side(i + 1, j), p01 = side(i, j + 1), p11 = side(i + 1, j + 1);
      b.tri(p00, p10, p11);
      b.tri(p00, p11, p01);
    }
  for (int top = 0; top < 2; ++top) {
    double z = top ? h : 0.0;
    auto cap = [&](int i, int ring) {
      if (ring == 0) return b.vertex(0, 0, z);
      double a = 2 * pi * (i % m) / m, rr = r * ring / c;
      return b.vertex(rr * std::cos(a), rr * std::sin(a), z);
    };
    for (int i = 0; i < m; ++i)
      for (int ring = 0; ring < c; ++ring) {
        uint32_t a0 = cap(i, ring), a1 = cap(i + 1, ring), b0 = cap(i, ring + 1), b1 = cap(i + 1, ring + 1);
        if (top) {
          if (ring > 0) b.tri(a0, b1, a1);
          b.tri(a0, b0, b1);
        } else {
          if (ring > 0) b.tri(a0, a1, b1);
          b.tri(a0, b1, b0);
        }
      }
  }
  return b.m;
}

//! Torus: major radius R, minor radius r, m × n quads split into triangles.
inline MeshBuffers torus(int m, int n, double R = 1.0, double r = 0.35) {
  Builder b;
  const double pi = 3.14159265358979323846;
  auto P = [&](int i, int j) {
    double u = 2 * pi * (i % m) / m, v = 2 * pi * (j % n) / n;
    return b.vertex((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
  };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      uint32_t p00 = P(i, j), p10 = P(i + 1, j), p01 = P(i, j + 1), p11 = P(i + 1, j + 1);
      b.tri(p00, p10, p11);
      b.tri(p00, p11, p01);
    }
  return b.m;
}

//! A ramp winding `turns` times round the z axis (radii r0..r1, rising `pitch` per turn): an
//! open strip of n × m quads. Above one turn its flat map, a sector of the annulus, overlaps itself.
inline MeshBuffers helicoidStrip(double turns, double r0, double r1, double pitch, int n, int m) {
  MeshBuffers M;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) {
      const double t = turns * 2 * M_PI * i / n, r = r0 + (r1 - r0) * j / m;
      M.positions.insert(M.positions.end(), {r * std::cos(t), r * std::sin(t), pitch * t / (2 * M_PI)});
    }
  auto id = [&](int i, int j) { return uint32_t(i * (m + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      M.triangles.insert(M.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      M.triangles.insert(M.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return M;
}

//! A flat square [0,1]^2 grid (open, one boundary loop).
inline MeshBuffers square(int n) {
  Builder b;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      uint32_t p00 = b.vertex(double(i) / n, double(j) / n, 0), p10 = b.vertex(double(i + 1) / n, double(j) / n, 0);
      uint32_t p01 = b.vertex(double(i) / n, double(j + 1) / n, 0), p11 = b.vertex(double(i + 1) / n, double(j + 1) / n, 0);
      b.tri(p00, p10, p11);
      b.tri(p00, p11, p01);
    }
  return b.m;
}

//! A flat n × n grid whose interior vertices are lifted by a deterministic pseudo-random height:
//! a coarse tessellation of a rough sheet, with many edges above 40° and no crease.
inline MeshBuffers roughSheet(int n, double amplitude) {
  MeshBuffers m = square(n);
  uint32_t state = 12345u;
  for (size_t v = 0; v < m.positions.size() / 3; ++v) {
    state = state * 1664525u + 1013904223u;
    const double x = m.positions[3 * v], y = m.positions[3 * v + 1];
    if (x > 0 && x < 1 && y > 0 && y < 1) m.positions[3 * v + 2] = amplitude * (double(state >> 8) / double(1u << 24) - 0.5);
  }
  return m;
}

//! A unit disk (30 rings, 64 sectors, centre vertex 0) raised to z = height(r).
template <typename Height>
MeshBuffers raisedDisk(Height height) {
  Builder b;
  const double pi = 3.14159265358979323846;
  const int rings = 30, sectors = 64;
  auto at = [&](int k, int i) {
    const double r = double(k) / rings, a = 2 * pi * (i % sectors) / sectors;
    return b.vertex(r * std::cos(a), r * std::sin(a), height(r));
  };
  const uint32_t centre = at(0, 0);  // first, so vertex 0 (arguments are evaluated in any order)
  for (int i = 0; i < sectors; ++i) {
    const uint32_t a = at(1, i), c = at(1, i + 1);
    b.tri(centre, a, c);
  }
  for (int k = 1; k < rings; ++k)
    for (int i = 0; i < sectors; ++i) {
      const uint32_t p00 = at(k, i), p10 = at(k + 1, i), p11 = at(k + 1, i + 1), p01 = at(k, i + 1);
      b.tri(p00, p10, p11);
      b.tri(p00, p11, p01);
    }
  return b.m;
}

//! The unit disk raised into a bump z = height·exp(-r²/width²): a finger whose tip, vertex 0,
//! gathers the curvature (the scale of a flattening sinks there).
inline MeshBuffers bump(double height, double width) {
  return raisedDisk([&](double r) { return height * std::exp(-r * r / (width * width)); });
}

//! The unit disk raised into a spike z = height·exp(-r/width): a horn whose tip, vertex 0, is a
//! cone of angle sum about 2π / sqrt(1 + (height/width)²); no edge bends by 40°, so no crease
//! reaches the tip.
inline MeshBuffers spike(double height, double width) {
  return raisedDisk([&](double r) { return height * std::exp(-r / width); });
}

}  // namespace conformesh::testshapes
