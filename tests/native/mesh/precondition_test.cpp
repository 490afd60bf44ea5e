#include <doctest/doctest.h>
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "features/test_shapes.h"
#include "mesh/precondition.h"
#include "quality/metrics.h"

using namespace conformesh;

namespace {

// A flat regular n-gon of radius 1 fan-triangulated from vertex 0: needles along the fan.
MeshBuffers needleFan(int n) {
  MeshBuffers m;
  for (int i = 0; i < n; ++i) m.positions.insert(m.positions.end(), {std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0.0});
  for (int i = 1; i + 1 < n; ++i) m.triangles.insert(m.triangles.end(), {0u, uint32_t(i), uint32_t(i + 1)});
  return m;
}

double area(const MeshBuffers& m, size_t f, double* nz = nullptr) {
  const uint32_t* t = &m.triangles[3 * f];
  const double* a = &m.positions[3 * t[0]];
  const double* b = &m.positions[3 * t[1]];
  const double* c = &m.positions[3 * t[2]];
  double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2], vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, z = ux * vy - uy * vx;
  if (nz) *nz = z;
  return 0.5 * std::sqrt(nx * nx + ny * ny + z * z);
}

double edgeLen(const MeshBuffers& m, uint32_t a, uint32_t b) {
  return std::hypot(m.positions[3 * a] - m.positions[3 * b], m.positions[3 * a + 1] - m.positions[3 * b + 1],
                    m.positions[3 * a + 2] - m.positions[3 * b + 2]);
}
}  // namespace

TEST_CASE("precondition: a needle fan is split and flipped, the surface and its orientation unchanged") {
  const MeshBuffers in = needleFan(40);
  PreconditionOptions o;
  o.maxEdgeLength = 0.2;
  const std::vector<std::array<uint32_t, 2>> prot = {{0u, 20u}};  // a fan diagonal, kept as an edge chain
  Preconditioned p = precondition(in, prot, o);
  const MeshBuffers& m = p.mesh;
  CHECK(p.splits > 0);
  CHECK(p.flips > 0);
  CHECK_FALSE(p.capped);
  REQUIRE(p.parents.size() == m.vertexCount());
  REQUIRE(p.faceOrigin.size() == m.triangleCount());
  // every edge at most the bound, every vertex on the input, same area, all facing +z
  double a0 = 0, a1 = 0;
  for (size_t f = 0; f < in.triangleCount(); ++f) a0 += area(in, f);
  quality::TriangleMeshDistance dist(in);
  for (size_t v = 0; v < m.vertexCount(); ++v) {
    const double d2 = dist.closest({m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}).distanceSquared;
    INFO("vertex " << v << " at " << m.positions[3 * v] << " " << m.positions[3 * v + 1] << " " << m.positions[3 * v + 2]);
    CHECK(m.positions[3 * v + 2] == 0.0);  // exactly in the plane
    CHECK(d2 < 1e-24);                     // inside the polygon (up to the distance query's rounding)
  }
  std::set<std::pair<uint32_t, uint32_t>> directed;
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    double nz = 0;
    a1 += area(m, f, &nz);
    CHECK(nz > 0);
    CHECK(p.faceOrigin[f] < in.triangleCount());
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = m.triangles[3 * f + c], b = m.triangles[3 * f + (c + 1) % 3];
      CHECK(edgeLen(m, a, b) <= 0.2 * (1 + 1e-12));
      CHECK(directed.insert({a, b}).second);  // manifold, consistently oriented
    }
  }
  CHECK(a1 == doctest::Approx(a0).epsilon(1e-12));
  // a disk still: V - E + F = 1
  std::set<std::pair<uint32_t, uint32_t>> undirected;
  for (auto [a, b] : directed) undirected.insert({std::min(a, b), std::max(a, b)});
  CHECK(int(m.vertexCount()) - int(undirected.size()) + int(m.triangleCount()) == 1);
  // the protected diagonal is a chain of mesh edges from vertex 0 to vertex 20 of total length 2
  double chain = 0;
  for (const auto& e : p.protectedEdges) {
    CHECK(undirected.count({std::min(e[0], e[1]), std::max(e[0], e[1])}) == 1);
    chain += edgeLen(m, e[0], e[1]);
  }
  CHECK(chain == doctest::Approx(2.0));
  // better triangles than the fan's needles (the ears at the polygon's corners stay: the
  // polygon's vertices are cocircular, those ears are Delaunay)
  const double meanIn = quality::angleStats(in).meanMinAngle, meanOut = quality::angleStats(m).meanMinAngle;
  MESSAGE("needle fan: mean min angle " << meanIn << " -> " << meanOut << " deg, " << p.splits << " splits, " << p.flips << " flips");
  CHECK(meanOut > 3 * meanIn);
}

TEST_CASE("precondition: sharp edges never flip (the cube keeps its faces), the vertex budget is a hard cap") {
  const MeshBuffers in = testshapes::cube(1);
  PreconditionOptions o;
  o.maxEdgeLength = 0.3;
  Preconditioned p = precondition(in, {}, o);
  const MeshBuffers& m = p.mesh;
  // every triangle lies in one face plane of the cube: its vertices share a coordinate at an extreme
  double lo = INFINITY, hi = -INFINITY;
  for (double c : in.positions) lo = std::min(lo, c), hi = std::max(hi, c);
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    bool planar = false;
    for (int k = 0; k < 3 && !planar; ++k)
      for (double ext : {lo, hi}) {
        bool all = true;
        for (int c = 0; c < 3; ++c) all = all && std::abs(m.positions[3 * m.triangles[3 * f + c] + k] - ext) < 1e-12;
        planar = planar || all;
      }
    CHECK(planar);
  }
  o.maxEdgeLength = 1e-3;
  o.maxNewVertices = 500;
  Preconditioned q = precondition(in, {}, o);
  CHECK(q.capped);
  CHECK(q.mesh.vertexCount() == in.vertexCount() + 500);
}

TEST_CASE("precondition: faceMask limits the changes to the marked triangles; none marked is the input as it is") {
  const MeshBuffers in = needleFan(40);
  PreconditionOptions o;
  o.maxEdgeLength = 0.2;
  o.faceMask.assign(in.triangleCount(), 0);
  const std::vector<std::array<uint32_t, 2>> prot = {{0u, 20u}, {3u, 30u}};  // the second is not an edge
  Preconditioned none = precondition(in, prot, o);
  CHECK(none.splits == 0);
  CHECK(none.flips == 0);
  CHECK(none.mesh.positions == in.positions);
  CHECK(none.mesh.triangles == in.triangles);
  REQUIRE(none.faceOrigin.size() == in.triangleCount());
  for (uint32_t f = 0; f < in.triangleCount(); ++f) CHECK(none.faceOrigin[f] == f);
  REQUIRE(none.protectedEdges.size() == 1);  // the editor's rule: pairs that are not edges are dropped
  CHECK(none.protectedEdges[0] == std::array<uint32_t, 2>{0u, 20u});
  // the first half marked: every triangle of the result lies in a marked input triangle or is one
  // of the unmarked input triangles unchanged
  for (uint32_t f = 0; f < in.triangleCount(); ++f) o.faceMask[f] = f < in.triangleCount() / 2;
  Preconditioned half = precondition(in, prot, o);
  CHECK(half.splits > 0);
  std::set<std::array<uint32_t, 3>> unmarked;
  for (uint32_t f = in.triangleCount() / 2; f < in.triangleCount(); ++f)
    unmarked.insert({in.triangles[3 * f], in.triangles[3 * f + 1], in.triangles[3 * f + 2]});
  size_t kept = 0;
  for (size_t f = 0; f < half.mesh.triangleCount(); ++f) {
    const std::array<uint32_t, 3> t{half.mesh.triangles[3 * f], half.mesh.triangles[3 * f + 1], half.mesh.triangles[3 * f + 2]};
    if (half.faceOrigin[f] >= in.triangleCount() / 2) kept += unmarked.count(t);
  }
  // an unmarked triangle changes only where it shares a split edge with a marked one (one here)
  CHECK(kept + 1 >= unmarked.size());
}
