// Mesh attributes through the readers and writers (OBJ vt / vn per corner, PLY colours, normals,
// scalars and texcoord lists), welding, seams and interpolation.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "mesh/mesh_attributes.h"
#include "mesh/mesh_io.h"
#include "mesh/weld_vertices.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

const MeshAttribute* find(const MeshBuffers& m, const std::string& name) {
  for (const MeshAttribute& a : m.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

// Per corner, the values of attribute `name` (or of mesh.uvs for "uv" per vertex): compares
// meshes whatever the attribute's kind.
std::vector<double> cornerValues(const MeshBuffers& m, const std::string& name) {
  std::vector<double> out;
  const MeshAttribute* a = find(m, name);
  if (!a && name == "uv" && !m.uvs.empty()) {
    for (uint32_t v : m.triangles) out.insert(out.end(), {m.uvs[2 * size_t(v)], m.uvs[2 * size_t(v) + 1]});
    return out;
  }
  REQUIRE(a != nullptr);
  for (size_t c = 0; c < m.triangles.size(); ++c) {
    const size_t item = a->perCorner ? c : m.triangles[c];
    out.insert(out.end(), &a->values[item * a->components], &a->values[item * a->components] + a->components);
  }
  return out;
}

// Two triangles of a square, the diagonal 1-2 a seam: vertex 2 has two vt and two vn, vertex 1
// one of each.
const char* kSquare =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.75\n"
    "vn 0 0 1\nvn 0 0.6 0.8\nvn 0.6 0 0.8\n"
    "f 1/1/1 2/2/2 3/3/1\nf 2/2/2 4/4/1 3/5/3\n";

}  // namespace

TEST_CASE("OBJ: vt and vn per corner where a vertex has several values; written back as read") {
  ReadResult r = readMesh(bytesOf(kSquare));
  CHECK(r.warnings.empty());
  CHECK(r.mesh.uvs.empty());
  const MeshAttribute* uv = find(r.mesh, "uv");
  const MeshAttribute* n = find(r.mesh, "normal");
  REQUIRE(uv);
  REQUIRE(n);
  CHECK(uv->perCorner);
  CHECK(n->perCorner);
  CHECK(cornerValues(r.mesh, "uv") == std::vector<double>{0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0.5, 0.75});
  // the seam: the diagonal only
  CHECK(attributeSeams(r.mesh) == std::vector<std::array<uint32_t, 2>>{{1, 2}});
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE}) {
    CAPTURE(formatName(f));
    ReadResult back = readMesh(writeMesh(r.mesh, f));
    CHECK(back.mesh.triangles == r.mesh.triangles);
    CHECK(cornerValues(back.mesh, "uv") == cornerValues(r.mesh, "uv"));
    if (f == MeshFormat::Obj) CHECK(cornerValues(back.mesh, "normal") == cornerValues(r.mesh, "normal"));
  }
  // with the uvs on one side only (no seam), the same file gives per-vertex uvs and no seam
  ReadResult plain = readMesh(bytesOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                      "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 2/2/1 4/4/1 3/3/1\n"));
  CHECK(plain.mesh.uvs.size() == 8);
  REQUIRE(find(plain.mesh, "normal"));
  CHECK_FALSE(find(plain.mesh, "normal")->perCorner);
  CHECK(attributeSeams(plain.mesh).empty());
  // not read when not asked for
  ReadOptions none;
  none.readUvs = false;
  none.readAttributes = false;
  CHECK(readMesh(bytesOf(kSquare), none).mesh.attributes.empty());
}

TEST_CASE("PLY: colours, normals and other scalar vertex properties become attributes and are written back") {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nproperty float quality\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string body = "0 0 0 0 0 1 255 0 51 0.5\n1 0 0 0 0 1 0 255 102 -2\n0 1 0 0 0 1 10 20 30 1e3\n3 0 1 2\n";
  ReadResult r = readMesh(bytesOf(header + body));
  const MeshAttribute* c = find(r.mesh, "color");
  const MeshAttribute* n = find(r.mesh, "normal");
  const MeshAttribute* q = find(r.mesh, "quality");
  REQUIRE(c);
  REQUIRE(n);
  REQUIRE(q);
  CHECK(c->components == 3);
  CHECK(c->values[0] == 1.0);
  CHECK(c->values[2] == doctest::Approx(0.2));
  CHECK(n->values == std::vector<double>{0, 0, 1, 0, 0, 1, 0, 0, 1});
  CHECK(q->values == std::vector<double>{0.5, -2, 1000});
  for (MeshFormat f : {MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE}) {
    CAPTURE(formatName(f));
    ReadResult back = readMesh(writeMesh(r.mesh, f));
    REQUIRE(back.mesh.attributes.size() == 3);
    for (const char* name : {"color", "normal", "quality"}) {
      const MeshAttribute *a = find(r.mesh, name), *b = find(back.mesh, name);
      REQUIRE(b);
      CHECK(b->perCorner == a->perCorner);
      REQUIRE(b->values.size() == a->values.size());
      for (size_t i = 0; i < a->values.size(); ++i) CHECK(b->values[i] == doctest::Approx(a->values[i]).epsilon(1e-12));
    }
  }
  // a non-finite value drops that property, with a warning; positions still must be finite
  ReadResult nan = readMesh(bytesOf(header + "0 0 0 0 0 1 255 0 51 nan\n1 0 0 0 0 1 0 255 102 -2\n0 1 0 0 0 1 10 20 30 1\n3 0 1 2\n"));
  CHECK_FALSE(find(nan.mesh, "quality"));
  CHECK(nan.warnings.size() == 1);
}

TEST_CASE("weld keeps every kept vertex's attributes; per-corner ones are untouched") {
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0};  // vertex 3 = vertex 1
  m.triangles = {0, 1, 2, 3, 4, 2};
  m.attributes.push_back(MeshAttribute{"quality", 1, false, {10, 11, 12, 13, 14}});
  m.attributes.push_back(MeshAttribute{"uv", 2, true, {0, 0, 1, 0, 0, 1, 5, 5, 6, 6, 7, 7}});
  CHECK(weldVertices(m) == 1);
  CHECK(m.triangles == std::vector<uint32_t>{0, 1, 2, 1, 3, 2});
  CHECK(m.attributes[0].values == std::vector<double>{10, 11, 12, 14});
  CHECK(m.attributes[1].values.size() == 12);
  CHECK_NOTHROW(checkAttributes(m, Stage::Api));
  m.attributes[0].values.pop_back();
  CHECK_THROWS_AS(checkAttributes(m, Stage::Api), Error);
}

TEST_CASE("interpolation is the barycentric combination; normals come back unit") {
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  m.triangles = {0, 1, 2};
  const MeshAttribute q{"quality", 1, false, {1, 2, 4}};
  const MeshAttribute uv{"uv", 2, true, {0, 0, 1, 0, 0, 1}};
  const MeshAttribute n{"normal", 3, false, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  const double b[3] = {0.5, 0.25, 0.25};
  double out[3];
  interpolateAttribute(m, q, 0, b, out);
  CHECK(out[0] == 0.5 + 0.5 + 1.0);
  interpolateAttribute(m, uv, 0, b, out);
  CHECK(out[0] == 0.25);
  CHECK(out[1] == 0.25);
  interpolateAttribute(m, n, 0, b, out);
  CHECK(std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]) == doctest::Approx(1.0));
  CHECK(out[0] == doctest::Approx(2 * out[1]));
}
