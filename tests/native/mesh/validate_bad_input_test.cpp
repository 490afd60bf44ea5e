// Bad inputs to validate(), meshInfo() and HalfedgeMesh::fromTriangles: each yields its
// documented status (validate.h) and never a crash. Also compiled with ASan + UBSan
// (conformesh_tests_asan).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mesh/halfedge_mesh.h"
#include "mesh/primitives.h"
#include "mesh/topology.h"
#include "mesh/validate.h"

using namespace conformesh;

namespace {
Code validateCode(const MeshBuffers& m, const ValidateOptions& o = {}) {
  try {
    validate(m, o);
  } catch (const Error& e) {
    CHECK(e.stage() == Stage::Validate);
    CHECK(std::string(e.what()).size() > 10);
    return e.code();
  }
  return Code::Ok;
}

Code infoCode(const MeshBuffers& m) {
  try {
    meshInfo(m);
  } catch (const Error& e) {
    return e.code();
  }
  return Code::Ok;
}

std::string validateMessage(const MeshBuffers& m) {
  try {
    validate(m);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool hasWarning(const std::vector<ValidationWarning>& ws, Code c) {
  return std::any_of(ws.begin(), ws.end(), [&](const ValidationWarning& w) { return w.code == c; });
}

MeshBuffers quad() {  // two triangles sharing edge (0, 2)
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.triangles = {0, 1, 2, 0, 2, 3};
  return m;
}
}  // namespace

TEST_CASE("bad input: empty mesh") {
  MeshBuffers none;
  CHECK(validateCode(none) == Code::EmptyMesh);
  CHECK(infoCode(none) == Code::EmptyMesh);
  MeshBuffers pointsOnly;
  pointsOnly.positions = {0, 0, 0, 1, 1, 1};
  CHECK(validateCode(pointsOnly) == Code::EmptyMesh);
  MeshBuffers allDegenerate;
  allDegenerate.positions = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  allDegenerate.triangles = {0, 1, 2, 0, 0, 1};
  CHECK(validateCode(allDegenerate) == Code::EmptyMesh);
  MeshInfo info = meshInfo(allDegenerate);  // counts, does not fail
  CHECK(info.faces == 0);
  CHECK(info.degenerateFaces == 2);
}

TEST_CASE("bad input: malformed arrays") {
  MeshBuffers m = quad();
  m.positions.pop_back();
  CHECK(validateCode(m) == Code::InvalidArgument);
  m = quad();
  m.triangles.push_back(1);
  CHECK(validateCode(m) == Code::InvalidArgument);
  m = quad();
  m.uvs = {0, 0, 1};
  CHECK(validateCode(m) == Code::InvalidArgument);
}

TEST_CASE("bad input: index out of range") {
  MeshBuffers m = quad();
  m.triangles[5] = 4;
  CHECK(validateCode(m) == Code::IndexOutOfRange);
  CHECK(infoCode(m) == Code::IndexOutOfRange);
  CHECK(validateMessage(m).find("triangle 1") != std::string::npos);
  m.triangles[5] = 0xffffffffu;
  CHECK(validateCode(m) == Code::IndexOutOfRange);
}

TEST_CASE("bad input: NaN and infinite coordinates") {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    MeshBuffers m = quad();
    m.positions[7] = bad;  // vertex 2
    CHECK(validateCode(m) == Code::NonFiniteCoordinate);
    CHECK(infoCode(m) == Code::NonFiniteCoordinate);
    CHECK(validateMessage(m).find("vertex 2") != std::string::npos);
  }
  MeshBuffers m = quad();
  m.uvs = {0, 0, 1, 0, 1, std::nan(""), 0, 1};
  CHECK(validateCode(m) == Code::NonFiniteCoordinate);
}

TEST_CASE("bad input: too large for the limits") {
  MeshBuffers m = makeIcosphere(2);
  ValidateOptions o;
  o.maxTriangles = m.triangleCount() - 1;
  CHECK(validateCode(m, o) == Code::TooLarge);
  o = ValidateOptions();
  o.maxVertices = m.vertexCount() - 1;
  CHECK(validateCode(m, o) == Code::TooLarge);
  o.maxVertices = m.vertexCount();
  CHECK(validateCode(m, o) == Code::Ok);
}

TEST_CASE("bad input: non-manifold edge (three triangles on one edge)") {
  MeshBuffers m = quad();
  m.positions.insert(m.positions.end(), {0.5, 0.5, 1.0});
  m.triangles.insert(m.triangles.end(), {2, 0, 4});  // a fin on edge (0, 2)
  CHECK(validateCode(m) == Code::NonManifoldEdge);
  std::string msg = validateMessage(m);
  CHECK(msg.find("(0, 2)") != std::string::npos);
  CHECK(msg.find("3 triangles") != std::string::npos);
  MeshInfo info = meshInfo(m);
  CHECK(info.nonManifoldEdges == 1);
  CHECK(info.faces == 3);
  CHECK(info.vertices == 5);
  CHECK(hasWarning(info.warnings, Code::NonManifoldEdge));
  CHECK_THROWS_AS(HalfedgeMesh::fromTriangles(5, m.triangles), Error);
}

TEST_CASE("bad input: bow-tie vertices") {
  // Two triangles touching at vertex 0 only (open fans).
  MeshBuffers open;
  open.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0};
  open.triangles = {0, 1, 2, 0, 3, 4};
  CHECK(validateCode(open) == Code::NonManifoldVertex);
  CHECK(validateMessage(open).find("vertex 0") != std::string::npos);
  MeshInfo info = meshInfo(open);
  CHECK(info.nonManifoldVertices == 1);
  CHECK(info.boundaryLoops == 2);  // the figure-eight boundary counts as two loops
  CHECK(hasWarning(info.warnings, Code::NonManifoldVertex));

  // Two closed tetrahedra sharing a vertex: no boundary at all, two fans at vertex 0.
  MeshBuffers tets;
  tets.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 1, -1, 0, 0, 0, -1, 0, -0.3, -0.3, -1};
  tets.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6};
  CHECK(validateCode(tets) == Code::NonManifoldVertex);
  MeshInfo ti = meshInfo(tets);
  CHECK(ti.nonManifoldVertices == 1);
  CHECK(ti.components == 1);
  ValidateOptions split;
  split.splitNonManifoldVertices = true;
  ValidatedMesh vm = validate(tets, split);
  CHECK(connectedComponents(vm.mesh).count == 2);
  CHECK(eulerCharacteristic(vm.mesh) == 4);
  CHECK(genus(vm.mesh) == 0);
}

TEST_CASE("bad input: mixed orientation is repaired with a warning") {
  MeshBuffers m = quad();
  std::swap(m.triangles[4], m.triangles[5]);  // second triangle reversed
  CHECK(validateCode(m) == Code::Ok);
  ValidatedMesh vm = validate(m);
  CHECK(vm.report.flippedFaces == 1);
  CHECK(hasWarning(vm.report.warnings, Code::InconsistentOrientation));
  MeshInfo info = meshInfo(m);
  CHECK(info.inconsistentFaces == 1);
  CHECK(hasWarning(info.warnings, Code::InconsistentOrientation));
  ValidateOptions strict;
  strict.fixOrientation = false;
  CHECK(validateCode(m, strict) == Code::InconsistentOrientation);
}

TEST_CASE("bad input: degenerate triangles are dropped with a warning") {
  MeshBuffers m = quad();
  m.positions.insert(m.positions.end(), {2, 0, 0});
  m.triangles.insert(m.triangles.end(), {0, 1, 4});  // collinear: (0,0,0) (1,0,0) (2,0,0)
  m.triangles.insert(m.triangles.end(), {2, 2, 3});  // repeated vertex
  m.triangles.insert(m.triangles.end(), {1, 1, 1});
  ValidatedMesh vm = validate(m);
  CHECK(vm.report.degenerateFaces == 3);
  CHECK(hasWarning(vm.report.warnings, Code::DegenerateFace));
  CHECK(vm.buffers.triangleCount() == 2);
  CHECK(meshInfo(m).degenerateFaces == 3);
  CHECK_THROWS_AS(HalfedgeMesh::fromTriangles(5, {0, 1, 1}), Error);
}

TEST_CASE("bad input: a Möbius strip is not orientable") {
  // A strip of n quads whose ends are glued with a half twist.
  const int n = 8;
  MeshBuffers m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double u = 2 * pi * i / n;
    for (int s = -1; s <= 1; s += 2) {
      double w = 0.3 * s;
      m.positions.insert(m.positions.end(), {(1 + w * std::cos(u / 2)) * std::cos(u),
                                             (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2)});
    }
  }
  for (int i = 0; i < n; ++i) {
    uint32_t a = 2 * i, b = 2 * i + 1;
    uint32_t c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;  // twist at the seam
    m.triangles.insert(m.triangles.end(), {a, c, d, a, d, b});
  }
  CHECK(validateCode(m) == Code::InvalidTopology);
  MeshInfo info = meshInfo(m);
  CHECK(hasWarning(info.warnings, Code::InvalidTopology));
  CHECK(info.boundaryLoops == 1);  // a Möbius strip has one boundary curve
  CHECK(info.euler == 0);
}

TEST_CASE("bad input: duplicate triangles") {
  MeshBuffers m = quad();
  m.triangles.insert(m.triangles.end(), {1, 2, 0});
  CHECK(validateCode(m) == Code::NonManifoldEdge);
  CHECK(meshInfo(m).duplicateFaces == 1);
}

TEST_CASE("bad input: random triangle soups never crash") {
  // Deterministic LCG; small vertex counts make every kind of defect likely.
  uint64_t s = 12345;
  auto next = [&]() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return uint32_t(s >> 33);
  };
  int ok = 0, failed = 0;
  for (int iter = 0; iter < 300; ++iter) {
    MeshBuffers m;
    const uint32_t nv = 3 + next() % 12, nf = 1 + next() % 20;
    for (uint32_t i = 0; i < 3 * nv; ++i) m.positions.push_back(double(next() % 5));
    for (uint32_t i = 0; i < 3 * nf; ++i) m.triangles.push_back(next() % (nv + (iter % 10 == 0 ? 1 : 0)));
    for (bool split : {false, true}) {
      ValidateOptions o;
      o.splitNonManifoldVertices = split;
      o.dropDuplicateFaces = split;
      try {
        ValidatedMesh vm = validate(m, o);
        CHECK_NOTHROW(vm.mesh.checkInvariants());
        CHECK(vm.mesh.toTriangles() == vm.buffers.triangles);
        CHECK(vm.faceToInput.size() == vm.buffers.triangleCount());
        ++ok;
      } catch (const Error& e) {
        CHECK(codeIsFatal(e.code()));
        ++failed;
      }
    }
    try {
      MeshInfo info = meshInfo(m);
      CHECK(info.faces + info.degenerateFaces == m.triangleCount());
    } catch (const Error& e) {
      CHECK(e.code() == Code::IndexOutOfRange);
    }
  }
  CHECK(ok > 0);
  CHECK(failed > 0);
}

TEST_CASE("bad input: mutated surfaces (holes, bow-ties, flips, duplicates) repair or fail cleanly") {
  uint64_t s = 987654321;
  auto next = [&]() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return uint32_t(s >> 33);
  };
  const MeshBuffers bases[] = {makeIcosphere(2), makeTorus(12, 6, 2.0, 0.6), makeAnnulus(2, 10, 1.0, 2.0)};
  int repaired = 0, splits = 0;
  for (int iter = 0; iter < 60; ++iter) {
    MeshBuffers m = bases[iter % 3];
    const size_t nf = m.triangleCount();
    std::vector<uint32_t> t;
    for (size_t f = 0; f < nf; ++f) {
      uint32_t r = next() % 100;
      if (r < 15) continue;  // remove: holes, and bow-ties where holes touch at a vertex
      uint32_t a = m.triangles[3 * f], b = m.triangles[3 * f + 1], c = m.triangles[3 * f + 2];
      if (r < 25) std::swap(b, c);  // reverse
      t.insert(t.end(), {a, b, c});
      if (r == 99) t.insert(t.end(), {b, c, a});  // duplicate
      if (r == 98) t.insert(t.end(), {a, a, c});  // degenerate
    }
    m.triangles = t;
    ValidateOptions o;
    o.splitNonManifoldVertices = true;
    o.dropDuplicateFaces = true;
    try {
      ValidatedMesh vm = validate(m, o);
      CHECK_NOTHROW(vm.mesh.checkInvariants());
      CHECK(vm.mesh.toTriangles() == vm.buffers.triangles);
      // The repaired surface is an oriented manifold: its counts obey the Euler–genus relation.
      long c = long(connectedComponents(vm.mesh).count), b = long(boundaryLoops(vm.mesh).size());
      CHECK((2 * c - eulerCharacteristic(vm.mesh) - b) % 2 == 0);
      CHECK(genus(vm.mesh) >= 0);
      ++repaired;
      splits += vm.report.splitVertices > 0 ? 1 : 0;
    } catch (const Error& e) {
      // A non-orientable result is possible only in theory here; nothing else may fail.
      CHECK(e.code() == Code::InvalidTopology);
    }
    CHECK_NOTHROW(meshInfo(m));
  }
  CHECK(repaired > 0);
  CHECK(splits > 0);
}
