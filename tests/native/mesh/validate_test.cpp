// validate(): the repairs (orientation, degenerate and duplicate triangles, bow-ties,
// unreferenced vertices) keep the surface and say what they did.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>

#include "mesh/mesh_geometry.h"
#include "mesh/topology.h"
#include "mesh/validate.h"
#include "mesh_test_util.h"

using namespace conformesh;

namespace {
bool hasWarning(const ValidationReport& r, Code c) {
  return std::any_of(r.warnings.begin(), r.warnings.end(), [&](const ValidationWarning& w) { return w.code == c; });
}

// Triangle f of a equals triangle f of b up to a rotation of its corners (same orientation).
bool sameOrientedTriangle(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, size_t f) {
  for (int r = 0; r < 3; ++r)
    if (a[3 * f] == b[3 * f + r] && a[3 * f + 1] == b[3 * f + (r + 1) % 3] && a[3 * f + 2] == b[3 * f + (r + 2) % 3])
      return true;
  return false;
}
}  // namespace

TEST_CASE("mixed orientation: the minority is reversed, per component") {
  for (const auto& nm : test::generatedMeshes()) {
    CAPTURE(nm.name);
    std::mt19937 rng(11);
    MeshBuffers m = nm.mesh;
    const size_t nf = m.triangleCount();
    size_t flipped = 0;
    for (size_t f = 0; f < nf; ++f)
      if (rng() % 4 == 0 && 2 * (flipped + 1) < nf) {  // about a quarter, always a minority
        std::swap(m.triangles[3 * f + 1], m.triangles[3 * f + 2]);
        ++flipped;
      }
    REQUIRE(flipped > 0);
    ValidatedMesh vm = validate(m);
    CHECK(vm.report.flippedFaces == flipped);
    CHECK(hasWarning(vm.report, Code::InconsistentOrientation));
    REQUIRE(vm.buffers.triangleCount() == nf);
    for (size_t f = 0; f < nf; ++f) CHECK(sameOrientedTriangle(vm.buffers.triangles, nm.mesh.triangles, f));
    CHECK_NOTHROW(vm.mesh.checkInvariants());
    CHECK(vm.mesh.toTriangles() == vm.buffers.triangles);

    ValidateOptions strict;
    strict.fixOrientation = false;
    try {
      validate(m, strict);
      FAIL("inconsistent orientation accepted with fixOrientation = false");
    } catch (const Error& e) {
      CHECK(e.code() == Code::InconsistentOrientation);
    }
  }
  // Majority reversed: the whole sphere comes out reversed (inward normals), consistently.
  MeshBuffers s = makeIcosphere(2);
  MeshBuffers r = s;
  for (size_t f = 0; f < r.triangleCount(); ++f)
    if (f % 5 != 0) std::swap(r.triangles[3 * f + 1], r.triangles[3 * f + 2]);
  ValidatedMesh vm = validate(r);
  CHECK(test::signedVolume(vm.buffers) < 0);
  CHECK(vm.report.flippedFaces == (s.triangleCount() + 4) / 5);
}

TEST_CASE("degenerate triangles are dropped, decided exactly") {
  MeshBuffers m = makeDisk(3, 10, 1.0);
  const size_t nf = m.triangleCount(), nv = m.vertexCount();
  // Far away: three exactly collinear points (dyadic steps on a line), a repeated-index triangle,
  // and a triangle one ulp off the line (not degenerate: kept, an extra component).
  const double a[3] = {5.0, 1.0, -2.0}, d[3] = {0.375, -1.25, 0.5};
  for (int k = 0; k < 3; ++k)
    m.positions.insert(m.positions.end(), {a[0] + k * d[0], a[1] + k * d[1], a[2] + k * d[2]});
  const uint32_t p = uint32_t(nv);
  m.triangles.insert(m.triangles.end(), {p, p + 1, p + 2});  // collinear
  m.triangles.insert(m.triangles.end(), {0, 1, 1});          // repeated vertex
  m.positions.insert(m.positions.end(), {a[0] + 2 * d[0], std::nextafter(a[1] + 2 * d[1], 10.0), a[2] + 2 * d[2]});
  m.positions.insert(m.positions.end(), {a[0] + d[0], a[1] + d[1], a[2] + d[2]});
  m.positions.insert(m.positions.end(), {a[0], a[1], a[2]});
  m.triangles.insert(m.triangles.end(), {p + 5, p + 4, p + 3});  // one ulp off the line

  CHECK(exactlyCollinear(&m.positions[3 * p], &m.positions[3 * (p + 1)], &m.positions[3 * (p + 2)]));
  CHECK_FALSE(exactlyCollinear(&m.positions[3 * (p + 5)], &m.positions[3 * (p + 4)], &m.positions[3 * (p + 3)]));

  ValidatedMesh vm = validate(m);
  CHECK(vm.report.degenerateFaces == 2);
  CHECK(vm.report.zeroAreaFaces == 1);
  CHECK(hasWarning(vm.report, Code::DegenerateFace));
  CHECK(vm.buffers.triangleCount() == nf + 1);
  CHECK(vm.report.removedVertices == 3);  // the collinear triangle's vertices are no longer used
  CHECK(connectedComponents(vm.mesh).count == 2);
  for (size_t f = 0; f < vm.buffers.triangleCount(); ++f) CHECK(vm.faceToInput[f] != nf);  // collinear one gone

  MeshInfo info = meshInfo(m);
  CHECK(info.degenerateFaces == 2);
  CHECK(info.faces == nf + 1);

  ValidateOptions keep;
  keep.dropZeroAreaFaces = false;
  ValidatedMesh kept = validate(m, keep);
  CHECK(kept.buffers.triangleCount() == nf + 2);
  CHECK(kept.report.zeroAreaFaces == 1);
}

TEST_CASE("exact collinearity: points on a lattice line are collinear, one ulp off is not") {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> small(-1000, 1000);
  for (int i = 0; i < 2000; ++i) {
    double a[3], d[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = std::ldexp(double(small(rng)), -7);
      d[k] = std::ldexp(double(small(rng)), -9);
    }
    int s = small(rng), t = small(rng);
    for (int k = 0; k < 3; ++k) {
      b[k] = a[k] + s * d[k];
      c[k] = a[k] + t * d[k];
    }
    CHECK(exactlyCollinear(a, b, c));
    int k = int(rng() % 3);
    bool across = d[(k + 1) % 3] != 0 || d[(k + 2) % 3] != 0;  // the nudge leaves the line
    if (s != 0 && t != 0 && s != t && across) {
      c[k] = std::nextafter(c[k], c[k] + 1.0);
      CHECK_FALSE(exactlyCollinear(a, b, c));
    }
  }
}

TEST_CASE("duplicate triangles: fatal by default, dropped on request") {
  MeshBuffers m = makeAnnulus(2, 8, 1.0, 2.0);
  const size_t nf = m.triangleCount();
  m.triangles.insert(m.triangles.end(), {m.triangles[6], m.triangles[8], m.triangles[7]});  // reversed copy of 2
  try {
    validate(m);
    FAIL("duplicate accepted");
  } catch (const Error& e) {
    CHECK(e.code() == Code::NonManifoldEdge);
    CHECK(std::string(e.what()).find("triangle " + std::to_string(nf)) != std::string::npos);
  }
  ValidateOptions o;
  o.dropDuplicateFaces = true;
  ValidatedMesh vm = validate(m, o);
  CHECK(vm.report.duplicateFaces == 1);
  CHECK(vm.buffers.triangleCount() == nf);
  CHECK(boundaryLoops(vm.mesh).size() == 2);
}

TEST_CASE("bow-tie vertices: split on request into manifold fans") {
  // Two fans around vertex 0: triangles (0,1,2),(0,2,3) and (0,4,5),(0,5,6).
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 0, 0, -1, -1, 0, 0, -1, 0};
  m.triangles = {0, 1, 2, 0, 2, 3, 0, 4, 5, 0, 5, 6};
  ValidateOptions o;
  o.splitNonManifoldVertices = true;
  ValidatedMesh vm = validate(m, o);
  CHECK(vm.report.splitVertices == 1);
  CHECK(hasWarning(vm.report, Code::NonManifoldVertex));
  CHECK(vm.mesh.vertexCount() == 8);
  CHECK(connectedComponents(vm.mesh).count == 2);
  CHECK(boundaryLoops(vm.mesh).size() == 2);
  CHECK_NOTHROW(vm.mesh.checkInvariants());
  CHECK(vm.mesh.toTriangles() == vm.buffers.triangles);
  CHECK(vm.vertexToInput[7] == 0);
  for (size_t v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) CHECK(vm.buffers.positions[3 * v + k] == m.positions[3 * vm.vertexToInput[v] + k]);
}

TEST_CASE("unreferenced vertices are removed; maps and uvs follow") {
  MeshBuffers m = makeDisk(2, 8, 1.0);
  const size_t nv = m.vertexCount();
  // Put an unused vertex in front by shifting every index, and give every vertex a uv.
  m.positions.insert(m.positions.begin(), {9.0, 9.0, 9.0});
  for (uint32_t& i : m.triangles) ++i;
  for (size_t v = 0; v <= nv; ++v) m.uvs.insert(m.uvs.end(), {double(v), -double(v)});
  ValidatedMesh vm = validate(m);
  CHECK(vm.report.removedVertices == 1);
  CHECK(vm.mesh.vertexCount() == nv);
  CHECK(vm.inputToVertex[0] == 0xffffffffu);
  REQUIRE(vm.buffers.uvs.size() == 2 * nv);
  for (size_t v = 0; v < nv; ++v) {
    uint32_t in = vm.vertexToInput[v];
    CHECK(vm.inputToVertex[in] == v);
    CHECK(vm.buffers.uvs[2 * v] == double(in));
    CHECK(vm.positions[VertexId(v)].x == m.positions[3 * in]);
  }
  for (size_t f = 0; f < vm.buffers.triangleCount(); ++f)
    for (int i = 0; i < 3; ++i)
      CHECK(vm.vertexToInput[vm.buffers.triangles[3 * f + i]] == m.triangles[3 * vm.faceToInput[f] + i]);
}
