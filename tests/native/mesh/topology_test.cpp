#include <doctest/doctest.h>
#include "core/constants.h"

#include <cmath>

#include "mesh/topology.h"
#include "mesh/validate.h"
#include "mesh_test_util.h"

using namespace conformesh;

namespace {

MeshBuffers disjointUnion(const MeshBuffers& a, const MeshBuffers& b, double shiftX) {
  MeshBuffers m = a;
  const uint32_t off = uint32_t(a.vertexCount());
  for (size_t v = 0; v < b.vertexCount(); ++v)
    m.positions.insert(m.positions.end(), {b.positions[3 * v] + shiftX, b.positions[3 * v + 1], b.positions[3 * v + 2]});
  for (uint32_t i : b.triangles) m.triangles.push_back(i + off);
  return m;
}

double cornerAngle(const Vec3& a, const Vec3& b, const Vec3& c) {  // angle at a
  Vec3 u = b - a, w = c - a;
  return std::atan2(norm(cross(u, w)), dot(u, w));
}
}  // namespace

TEST_CASE("Euler characteristic, genus and boundary loops of generated surfaces") {
  for (const auto& nm : test::generatedMeshes()) {
    CAPTURE(nm.name);
    ValidatedMesh vm = validate(nm.mesh);
    CHECK(vm.report.warnings.empty());
    const HalfedgeMesh& hm = vm.mesh;
    CHECK(eulerCharacteristic(hm) == nm.chi);
    CHECK(genus(hm) == nm.genus);
    CHECK(connectedComponents(hm).count == 1);
    auto loops = boundaryLoops(hm);
    CHECK(loops.size() == nm.loops);

    // meshInfo (counting, no halfedges) agrees with the halfedge queries, in any vertex order.
    for (uint32_t seed = 0; seed < 2; ++seed) {
      MeshInfo info = meshInfo(seed ? test::shuffled(nm.mesh, seed) : nm.mesh);
      CHECK(info.vertices == hm.vertexCount());
      CHECK(info.faces == hm.faceCount());
      CHECK(info.edges == hm.edgeCount());
      CHECK(info.euler == eulerCharacteristic(hm));
      CHECK(info.genus == double(genus(hm)));
      CHECK(info.boundaryLoops == loops.size());
      CHECK(info.components == 1);
      CHECK(info.nonManifoldEdges == 0);
      CHECK(info.degenerateFaces == 0);
      CHECK(info.warnings.empty());
    }
  }
}

TEST_CASE("boundary loops are closed, ordered chains of boundary halfedges") {
  MeshBuffers disk = makeDisk(4, 12, 2.0);
  ValidatedMesh vm = validate(test::shuffled(disk, 7));
  auto loops = boundaryLoops(vm.mesh);
  REQUIRE(loops.size() == 1);
  size_t total = 0;
  for (const auto& loop : loops) {
    total += loop.size();
    for (size_t i = 0; i < loop.size(); ++i) {
      HalfedgeId h = loop[i], n = loop[(i + 1) % loop.size()];
      CHECK(vm.mesh.isBoundary(h));
      CHECK(vm.mesh.next(h) == n);
      CHECK(vm.mesh.tip(h) == vm.mesh.tail(n));
      // On the disk's rim: radius 2.
      CHECK(norm(vm.positions[vm.mesh.tail(h)]) == doctest::Approx(2.0));
    }
  }
  CHECK(total == vm.mesh.boundaryHalfedgeCount());

  // Annulus: the outer loop turns by +2π seen from above? No: boundary halfedges run clockwise
  // around the surface, so the outer loop is clockwise (negative signed area) and the hole's
  // loop counter-clockwise.
  ValidatedMesh an = validate(makeAnnulus(2, 16, 1.0, 2.0));
  auto aloops = boundaryLoops(an.mesh);
  REQUIRE(aloops.size() == 2);
  for (const auto& loop : aloops) {
    double area = 0, r = norm(an.positions[an.mesh.tail(loop[0])]);
    for (HalfedgeId h : loop) {
      Vec3 p = an.positions[an.mesh.tail(h)], q = an.positions[an.mesh.tip(h)];
      area += 0.5 * (p.x * q.y - q.x * p.y);
      CHECK(norm(p) == doctest::Approx(r));
    }
    if (r > 1.5)
      CHECK(area < 0);
    else
      CHECK(area > 0);
  }
}

TEST_CASE("discrete Gauss-Bonnet: total angle defect = 2π χ") {
  for (const auto& nm : test::generatedMeshes()) {
    CAPTURE(nm.name);
    ValidatedMesh vm = validate(nm.mesh);
    const HalfedgeMesh& hm = vm.mesh;
    VertexData<double> angleSum(hm, 0.0);
    for (FaceId f : hm.faces()) {
      for (HalfedgeId h : hm.faceHalfedges(f)) {
        VertexId a = hm.tail(h);
        angleSum[a] += cornerAngle(vm.positions[a], vm.positions[hm.tip(h)], vm.positions[hm.tail(hm.prev(h))]);
      }
    }
    double total = 0;
    for (VertexId v : hm.vertices()) total += (hm.isBoundary(v) ? kPi : 2 * kPi) - angleSum[v];
    CHECK(total == doctest::Approx(2 * kPi * double(eulerCharacteristic(hm))).epsilon(1e-9).scale(1.0));
  }
}

TEST_CASE("components, χ and genus add up over a disjoint union") {
  MeshBuffers m = disjointUnion(makeIcosphere(2), makeTorus(16, 8, 2.0, 0.5), 5.0);
  m = disjointUnion(m, makeAnnulus(2, 12, 1.0, 2.0), -5.0);
  ValidatedMesh vm = validate(m);
  Components c = connectedComponents(vm.mesh);
  CHECK(c.count == 3);
  CHECK(eulerCharacteristic(vm.mesh) == 2 + 0 + 0);
  CHECK(genus(vm.mesh) == 0 + 1 + 0);
  CHECK(boundaryLoops(vm.mesh).size() == 2);
  for (FaceId f : vm.mesh.faces())
    for (HalfedgeId h : vm.mesh.faceHalfedges(f)) {
      CHECK(c.vertexComponent[vm.mesh.tail(h)] == c.faceComponent[f]);
      if (!vm.mesh.isBoundary(vm.mesh.twin(h))) CHECK(c.faceComponent[vm.mesh.face(vm.mesh.twin(h))] == c.faceComponent[f]);
    }
  MeshInfo info = meshInfo(m);
  CHECK(info.components == 3);
  CHECK(info.genus == 1.0);
  CHECK(info.boundaryLoops == 2);
}

TEST_CASE("dihedral angles: cube edges +90°, flat 0°, hole corners concave") {
  const int n = 3;
  ValidatedMesh cube = validate(makeCube(n, 1.0));
  EdgeData<double> a = dihedralAngles(cube.mesh, cube.positions);
  size_t sharp = 0;
  for (EdgeId e : cube.mesh.edges()) {
    HalfedgeId h = cube.mesh.halfedge(e);
    Vec3 p = cube.positions[cube.mesh.tail(h)], q = cube.positions[cube.mesh.tip(h)];
    // An edge of the cube itself has both ends on two of the cube's faces (two coordinates ±1).
    auto onTwoFaces = [](const Vec3& x) {
      int k = 0;
      for (int i = 0; i < 3; ++i) k += std::fabs(std::fabs(x[i]) - 1.0) < 1e-12 ? 1 : 0;
      return k >= 2;
    };
    const Vec3 d = p - q;
    int same = 0;  // coordinates the two ends share
    for (int i = 0; i < 3; ++i) same += std::fabs(d[i]) < 1e-12 ? 1 : 0;
    bool cubeEdge = onTwoFaces(p) && onTwoFaces(q) && same == 2;
    if (cubeEdge) {
      ++sharp;
      CHECK(a[e] == doctest::Approx(kPi / 2).epsilon(1e-12));
    } else {
      CHECK(std::fabs(a[e]) < 1e-12);
    }
  }
  CHECK(sharp == size_t(12 * n));
  EdgeData<uint8_t> s = sharpEdges(cube.mesh, cube.positions, 40.0 * kPi / 180.0);
  size_t flagged = 0;
  for (EdgeId e : cube.mesh.edges()) flagged += s[e];
  CHECK(flagged == sharp);

  // Box with a square hole: every angle is 0 or ±90°; the concave ones are the hole's vertical
  // corner edges (|x| = |y| = hole half size).
  const double hole = 0.4;
  ValidatedMesh box = validate(makeBoxWithHole(2, 1.0, hole, 0.5));
  EdgeData<double> b = dihedralAngles(box.mesh, box.positions);
  size_t concave = 0;
  for (EdgeId e : box.mesh.edges()) {
    double x = b[e];
    bool right = std::fabs(std::fabs(x) - kPi / 2) < 1e-9, flat = std::fabs(x) < 1e-9;
    CHECK((right || flat));
    if (x < -1e-9) {
      ++concave;
      HalfedgeId h = box.mesh.halfedge(e);
      Vec3 p = box.positions[box.mesh.tail(h)], q = box.positions[box.mesh.tip(h)];
      CHECK(p.x == doctest::Approx(q.x));
      CHECK(p.y == doctest::Approx(q.y));
      CHECK(std::fabs(p.x) == doctest::Approx(hole));
      CHECK(std::fabs(p.y) == doctest::Approx(hole));
    }
  }
  CHECK(concave > 0);

  // A convex closed surface: every dihedral angle positive; a plane: all zero.
  ValidatedMesh sphere = validate(makeIcosphere(2));
  EdgeData<double> c = dihedralAngles(sphere.mesh, sphere.positions);
  for (EdgeId e : sphere.mesh.edges()) CHECK(c[e] > 0);
  ValidatedMesh flat = validate(makeAnnulus(2, 10, 1.0, 2.0));
  EdgeData<double> d = dihedralAngles(flat.mesh, flat.positions);
  for (EdgeId e : flat.mesh.edges()) CHECK(d[e] == 0.0);
}
