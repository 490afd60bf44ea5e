// Shared checks for the planar tests: properties of a PlanarMesh, computed independently of the
// library's own bookkeeping (exact predicates only).
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <fstream>
#include <iterator>
#include "planar/cdt.h"
#include "planar/poly_io.h"
#include "planar/predicates.h"

namespace planar_test {

using namespace conformesh;
using namespace conformesh::planar;

inline std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  REQUIRE_MESSAGE(f.good(), "cannot open " << path);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

inline Pslg loadPoly(const std::string& name) {
  return readPoly(readBytes(std::string(CONFORMESH_DATA_DIR) + "/pslg/" + name + ".poly"));
}

inline const double* P(const PlanarMesh& m, uint32_t v) { return &m.points[2 * size_t(v)]; }

inline double triMinAngleDeg(const double* a, const double* b, const double* c) {
  auto ang = [](const double* p, const double* q, const double* r) {
    double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy);
  };
  double m = std::min(ang(a, b, c), std::min(ang(b, c, a), ang(c, a, b)));
  return m * 180.0 / 3.14159265358979323846;
}

struct MeshCheck {
  size_t inverted = 0;          // triangles not strictly counter-clockwise
  size_t nonManifold = 0;       // edges used twice in the same direction or by > 2 triangles
  size_t notDelaunay = 0;       // unconstrained interior edges failing the exact incircle test
  size_t segmentsBroken = 0;    // input segments not present as a chain of constrained edges
  size_t inputMissing = 0;      // input vertices on a segment that no triangle uses
  size_t paramOff = 0;          // vertices whose (segment, t) does not reproduce the point
  double minAngle = 180;
  size_t belowAngle(const PlanarMesh& m, double theta) const {
    size_t n = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t)
      if (triMinAngleDeg(P(m, m.triangles[3 * t]), P(m, m.triangles[3 * t + 1]), P(m, m.triangles[3 * t + 2])) <
          theta)
        ++n;
    return n;
  }
};

inline MeshCheck checkMesh(const PlanarMesh& m, const Pslg& in, bool delaunay) {
  MeshCheck r;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> half;  // directed edge -> opposite vertex
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* v = &m.triangles[3 * t];
    if (orient2d(P(m, v[0]), P(m, v[1]), P(m, v[2])) <= 0) ++r.inverted;
    r.minAngle = std::min(r.minAngle, triMinAngleDeg(P(m, v[0]), P(m, v[1]), P(m, v[2])));
    for (int i = 0; i < 3; ++i) {
      auto key = std::make_pair(v[(i + 1) % 3], v[(i + 2) % 3]);
      if (!half.emplace(key, v[i]).second) ++r.nonManifold;
    }
  }
  std::map<std::pair<uint32_t, uint32_t>, int32_t> con;
  for (size_t e = 0; e < m.edges.size() / 2; ++e) {
    uint32_t a = m.edges[2 * e], b = m.edges[2 * e + 1];
    con[{std::min(a, b), std::max(a, b)}] = m.edgeSegment[e];
  }
  if (delaunay) {
    for (const auto& [key, apex] : half) {
      auto it = half.find({key.second, key.first});
      if (it == half.end()) continue;
      if (con.count({std::min(key.first, key.second), std::max(key.first, key.second)})) continue;
      if (incircle(P(m, key.first), P(m, key.second), P(m, apex), P(m, it->second)) > 0) ++r.notDelaunay;
    }
  }
  // Every input segment is a chain of constrained edges from one endpoint to the other.
  std::vector<std::vector<uint32_t>> adj;
  size_t nseg = in.segments.size() / 2;
  std::vector<std::map<uint32_t, std::vector<uint32_t>>> chains(nseg);
  for (const auto& [key, seg] : con) {
    if (seg < 0) continue;
    chains[size_t(seg)][key.first].push_back(key.second);
    chains[size_t(seg)][key.second].push_back(key.first);
  }
  for (size_t s = 0; s < nseg; ++s) {
    uint32_t a = in.segments[2 * s], b = in.segments[2 * s + 1];
    // follow the chain from a
    uint32_t prev = a, cur = a;
    size_t steps = 0;
    auto& ch = chains[s];
    bool ok = ch.count(a) && ch[a].size() == 1;
    while (ok && cur != b && steps++ < ch.size() + 2) {
      auto& nb = ch[cur];
      uint32_t next = nb[0] == prev && nb.size() > 1 ? nb[1] : nb[0];
      if (next == prev) {
        ok = false;
        break;
      }
      // collinear with the segment (exact)
      if (orient2d(&in.points[2 * a], &in.points[2 * b], P(m, next)) != 0 &&
          std::fabs(orient2d(&in.points[2 * a], &in.points[2 * b], P(m, next))) >
              1e-12 * (std::fabs(in.points[2 * a]) + std::fabs(in.points[2 * b]) + 1))
        ok = false;
      prev = cur;
      cur = next;
    }
    if (!ok || cur != b) ++r.segmentsBroken;
  }
  std::vector<char> used(m.vertexCount(), 0);
  for (uint32_t v : m.triangles) used[v] = 1;
  for (uint32_t v : in.segments)
    if (!used[v]) ++r.inputMissing;
  for (size_t v = 0; v < m.vertexCount(); ++v) {
    int32_t s = m.vertexSegment[v];
    if (s < 0) continue;
    const double* A = &in.points[2 * size_t(in.segments[2 * size_t(s)])];
    const double* B = &in.points[2 * size_t(in.segments[2 * size_t(s) + 1])];
    double t = m.vertexParam[v];
    double x = A[0] + t * (B[0] - A[0]), y = A[1] + t * (B[1] - A[1]);
    double scale = std::fabs(A[0]) + std::fabs(A[1]) + std::fabs(B[0]) + std::fabs(B[1]) + 1e-300;
    if (std::fabs(x - m.points[2 * v]) > 1e-12 * scale || std::fabs(y - m.points[2 * v + 1]) > 1e-12 * scale ||
        t < 0 || t > 1)
      ++r.paramOff;
  }
  return r;
}

inline double meshArea(const PlanarMesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const double* p = P(m, m.triangles[3 * t]);
    const double* q = P(m, m.triangles[3 * t + 1]);
    const double* r = P(m, m.triangles[3 * t + 2]);
    a += 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
  }
  return a;
}

}  // namespace planar_test
