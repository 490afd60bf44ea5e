// Welding: exact weld undoes duplication; tolerance weld equals a brute-force reference of the
// documented rule; determinism; bad tolerances.
#include <doctest/doctest.h>

#include <cmath>

#include "mesh/mesh_io.h"
#include "mesh/weld_vertices.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

// Reference for the tolerance rule, O(n^2): each vertex merges into the lowest-indexed earlier
// kept vertex within distance tol.
std::vector<uint32_t> bruteForceRepresentatives(const std::vector<double>& p, double tol) {
  const size_t n = p.size() / 3;
  std::vector<uint32_t> rep(n);
  for (size_t v = 0; v < n; ++v) {
    rep[v] = uint32_t(v);
    for (size_t r = 0; r < v; ++r) {
      if (rep[r] != r) continue;
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (p[3 * v + k] - p[3 * r + k]) * (p[3 * v + k] - p[3 * r + k]);
      if (d2 <= tol * tol) {
        rep[v] = uint32_t(r);
        break;
      }
    }
  }
  return rep;
}

// Mesh with every vertex duplicated `copies` times (copies jittered by up to `jitter`).
MeshBuffers duplicated(const MeshBuffers& m, int copies, double jitter, uint64_t seed) {
  Rng r(seed);
  const size_t nv = m.vertexCount();
  MeshBuffers d;
  for (int c = 0; c < copies; ++c)
    for (size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) d.positions.push_back(m.positions[3 * v + k] + (c ? jitter * (2 * r.uniform() - 1) : 0.0));
  for (uint32_t t : m.triangles) d.triangles.push_back(uint32_t(t + nv * r.below(uint32_t(copies))));
  return d;
}

}  // namespace

TEST_CASE("exact weld undoes duplication and keeps first positions") {
  MeshBuffers m = toBuffers(randomPolyMesh(70, 200, 300), false);
  m.positions[0] = 0.0;
  MeshBuffers d = duplicated(m, 3, 0.0, 1);
  d.positions[3 * m.vertexCount()] = -0.0;  // the copy of vertex 0 has x = -0: still equal
  MeshBuffers e = d;
  size_t removed = weldVertices(e, 0.0);
  // Every vertex and its copies become one vertex (the first copy), order kept.
  CHECK(e.vertexCount() == m.vertexCount());
  CHECK(removed == 2 * m.vertexCount());
  CHECK(e.positions == m.positions);
  for (size_t c = 0; c < d.triangles.size(); ++c)
    for (int k = 0; k < 3; ++k)
      CHECK(e.positions[3 * size_t(e.triangles[c]) + k] + 0.0 == d.positions[3 * size_t(d.triangles[c]) + k] + 0.0);
}

TEST_CASE("tolerance weld equals the brute-force rule, deterministically") {
  for (uint64_t seed = 80; seed < 86; ++seed) {
    Rng r(seed);
    // Clustered points: many pairs closer than tol, chains, and exact duplicates.
    MeshBuffers m;
    const double tol = 0.05;
    for (int i = 0; i < 600; ++i) {
      if (i > 0 && r.below(5) == 0) {  // exact copy of an earlier point
        uint32_t j = r.below(uint32_t(i));
        for (int k = 0; k < 3; ++k) m.positions.push_back(m.positions[3 * j + k]);
        continue;
      }
      for (int k = 0; k < 3; ++k) m.positions.push_back(std::floor(r.uniform() * 8) * 0.07 + r.uniform() * 0.03 - 1.0);
    }
    for (uint32_t i = 0; i + 2 < 600; ++i) m.triangles.insert(m.triangles.end(), {i, i + 1, i + 2});
    std::vector<uint32_t> rep = bruteForceRepresentatives(m.positions, tol);
    MeshBuffers w = m;
    weldVertices(w, tol);
    // Renumber the reference and compare.
    std::vector<uint32_t> idx(rep.size());
    uint32_t next = 0;
    for (size_t v = 0; v < rep.size(); ++v)
      if (rep[v] == v) idx[v] = next++;
    CHECK(w.vertexCount() == next);
    bool same = true;
    for (size_t c = 0; c < m.triangles.size(); ++c) same &= w.triangles[c] == idx[rep[m.triangles[c]]];
    CHECK(same);
    MeshBuffers w2 = m;
    weldVertices(w2, tol);
    CHECK(w2.positions == w.positions);
    CHECK(w2.triangles == w.triangles);
  }
}

TEST_CASE("tolerance weld through readMesh, and bad tolerances") {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1.0000001 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 3\n";
  ReadOptions o;
  o.weldTolerance = 1e-6;
  ReadResult r = readMesh(std::vector<uint8_t>(obj.begin(), obj.end()), o);
  CHECK(r.mesh.vertexCount() == 4);
  CHECK(r.mesh.triangles == std::vector<uint32_t>{0, 1, 2, 1, 3, 2});
  CHECK(r.warnings.size() == 1);
  MeshBuffers m = r.mesh;
  auto codeOf = [&](double tol) {
    try {
      MeshBuffers c = m;
      weldVertices(c, tol);
    } catch (const Error& e) {
      return e.code();
    }
    return Code::Ok;
  };
  CHECK(codeOf(-1.0) == Code::InvalidArgument);
  CHECK(codeOf(std::nan("")) == Code::InvalidArgument);
  CHECK(codeOf(INFINITY) == Code::InvalidArgument);
  CHECK(codeOf(1e-300) == Code::InvalidArgument);  // 1 / 1e-300 cells: the grid would overflow
  o.weldTolerance = -1;
  CHECK_THROWS_AS(readMesh(std::vector<uint8_t>(obj.begin(), obj.end()), o), Error);
}
