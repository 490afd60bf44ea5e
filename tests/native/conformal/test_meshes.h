// Mesh generators and a small OBJ/OFF reader for the flatten tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh::testmesh {

//! Polar grid on the unit disk: centre, `rings` rings of `m` points at radius k/rings, the
//! outer ring a regular m-gon. `twist` rotates ring k by k*twist radians (makes slivers).
inline MeshBuffers polarDisk(int rings, int m, double twist = 0.0) {
  MeshBuffers M;
  M.positions = {0, 0, 0};
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < m; ++j) {
      const double a = 2 * M_PI * j / m + k * twist, r = double(k) / rings;
      M.positions.insert(M.positions.end(), {r * std::cos(a), r * std::sin(a), 0.0});
    }
  auto id = [&](int k, int j) { return uint32_t(1 + (k - 1) * m + (j % m)); };
  for (int j = 0; j < m; ++j) M.triangles.insert(M.triangles.end(), {0u, id(1, j), id(1, j + 1)});
  for (int k = 1; k < rings; ++k)
    for (int j = 0; j < m; ++j) {
      M.triangles.insert(M.triangles.end(), {id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      M.triangles.insert(M.triangles.end(), {id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  return M;
}

//! The polar disk wrapped onto the unit sphere: ring k at polar angle k/rings * phiMax.
inline MeshBuffers sphericalCap(int rings, int m, double phiMax, double twist = 0.0) {
  MeshBuffers M = polarDisk(rings, m, twist);
  for (size_t v = 0; v < M.vertexCount(); ++v) {
    double* p = &M.positions[3 * v];
    const double r = std::hypot(p[0], p[1]), a = std::atan2(p[1], p[0]), phi = r * phiMax;
    p[0] = std::sin(phi) * std::cos(a);
    p[1] = std::sin(phi) * std::sin(a);
    p[2] = std::cos(phi);
  }
  return M;
}

//! Annulus (rings between radius r0 and 1), optionally lifted onto a paraboloid z = c r^2.
inline MeshBuffers annulus(int rings, int m, double r0, double c = 0.0) {
  MeshBuffers M;
  for (int k = 0; k <= rings; ++k)
    for (int j = 0; j < m; ++j) {
      const double a = 2 * M_PI * (j + 0.5 * k) / m, r = r0 + (1 - r0) * k / rings;
      M.positions.insert(M.positions.end(), {r * std::cos(a), r * std::sin(a), c * r * r});
    }
  auto id = [&](int k, int j) { return uint32_t(k * m + (j % m)); };
  for (int k = 0; k < rings; ++k)
    for (int j = 0; j < m; ++j) {
      M.triangles.insert(M.triangles.end(), {id(k, j), id(k, j + 1), id(k + 1, j)});
      M.triangles.insert(M.triangles.end(), {id(k, j + 1), id(k + 1, j + 1), id(k + 1, j)});
    }
  return M;
}

//! Minimal OBJ / OFF reader for test data (triangles and fan-triangulated polygons).
inline MeshBuffers readTestMesh(const std::string& path) {
  MeshBuffers M;
  std::ifstream in(path);
  if (!in) return M;
  const bool off = path.size() > 4 && path.substr(path.size() - 4) == ".off";
  std::string line;
  auto addPoly = [&](const std::vector<long>& poly) {
    for (size_t i = 1; i + 1 < poly.size(); ++i)
      M.triangles.insert(M.triangles.end(), {uint32_t(poly[0]), uint32_t(poly[i]), uint32_t(poly[i + 1])});
  };
  if (off) {
    std::string header;
    in >> header;
    long nv, nf, ne;
    in >> nv >> nf >> ne;
    M.positions.resize(3 * nv);
    for (long i = 0; i < 3 * nv; ++i) in >> M.positions[i];
    for (long f = 0; f < nf; ++f) {
      int n;
      in >> n;
      std::vector<long> poly(n);
      for (auto& x : poly) in >> x;
      std::getline(in, line);
      addPoly(poly);
    }
    return M;
  }
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      double x, y, z;
      ss >> x >> y >> z;
      M.positions.insert(M.positions.end(), {x, y, z});
    } else if (tag == "f") {
      std::vector<long> poly;
      std::string tok;
      while (ss >> tok) {
        long i = std::stol(tok.substr(0, tok.find('/')));
        poly.push_back(i < 0 ? long(M.vertexCount()) + i : i - 1);
      }
      addPoly(poly);
    }
  }
  return M;
}

}  // namespace conformesh::testmesh

namespace conformesh::testmesh {
//! A CAD-like planar strip [0, len] x [0, 1] meshed as a fan of needles: the bottom edge has n
//! segments, the top edge one; every bottom vertex connects to the top-left corner, the last
//! triangle uses the top-right corner. Apex angles ~ 1/(len n) rad.
inline MeshBuffers needleStrip(double len, int n) {
  MeshBuffers M;
  for (int i = 0; i <= n; ++i) M.positions.insert(M.positions.end(), {len * i / n, 0.0, 0.0});
  const uint32_t tl = uint32_t(n + 1), tr = uint32_t(n + 2);
  M.positions.insert(M.positions.end(), {0.0, 1.0, 0.0});
  M.positions.insert(M.positions.end(), {len, 1.0, 0.0});
  for (int i = 0; i < n; ++i) M.triangles.insert(M.triangles.end(), {uint32_t(i), uint32_t(i + 1), tl});
  M.triangles.insert(M.triangles.end(), {uint32_t(n), tr, tl});
  return M;
}
}  // namespace conformesh::testmesh

namespace conformesh::testmesh {
//! A CAD-like strip [0, len] x [0, 1], nx by ny cells split by one diagonal, bent into a saddle
//! z = bend (x'^2 - y'^2) (x', y' centred): with nx >> ny every triangle is a needle.
inline MeshBuffers needleGrid(double len, int nx, int ny, double bend) {
  MeshBuffers M;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = len * i / nx, y = double(j) / ny, xc = x - 0.5 * len, yc = y - 0.5;
      M.positions.insert(M.positions.end(), {x, y, bend * (xc * xc - yc * yc)});
    }
  auto id = [&](int i, int j) { return uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      M.triangles.insert(M.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      M.triangles.insert(M.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return M;
}
}  // namespace conformesh::testmesh

namespace conformesh::testmesh {
//! A jagged patch: the n x n unit grid (cells split by a diagonal) without the cells with
//! i + j < k or (n-1-i) + (n-1-j) < k, so two opposite corners become staircases of 90 and
//! 270 degree turns, lifted onto the paraboloid z = c ((x - 1/2)^2 + (y - 1/2)^2).
inline MeshBuffers staircase(int n, int k, double c) {
  MeshBuffers M;
  std::vector<int> id(size_t(n + 1) * (n + 1), -1);
  auto vertex = [&](int i, int j) {
    int& v = id[size_t(i) * (n + 1) + j];
    if (v < 0) {
      v = int(M.positions.size() / 3);
      const double x = double(i) / n, y = double(j) / n;
      M.positions.insert(M.positions.end(), {x, y, c * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5))});
    }
    return uint32_t(v);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i + j < k || (n - 1 - i) + (n - 1 - j) < k) continue;
      const uint32_t a = vertex(i, j), b = vertex(i + 1, j), d = vertex(i + 1, j + 1), e = vertex(i, j + 1);
      M.triangles.insert(M.triangles.end(), {a, b, d, a, d, e});
    }
  return M;
}
}  // namespace conformesh::testmesh
