// OBJ reader: every face syntax, relative indices, comments, CRLF, uvs, and its errors.
#include <doctest/doctest.h>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

enum class Corner { Plain, WithUv, WithUvNormal, WithNormal };

// OBJ text for m: vertices (with optional w and colour values), vt/vn lines, faces in the given
// corner syntax, indices relative (negative) or absolute; CRLF or LF; comments sprinkled in.
std::string objText(const PolyMesh& m, Corner corner, bool relative, bool crlf, bool extras) {
  const std::string nl = crlf ? "\r\n" : "\n";
  std::string s = "# test mesh" + nl + "mtllib none.mtl" + nl + "o thing" + nl;
  const size_t nv = m.positions.size() / 3;
  // Faces are written after all vertices; relative indices are then -(nv - i).
  for (size_t v = 0; v < nv; ++v) {
    s += "v " + num(m.positions[3 * v]) + (extras ? "\t " : " ") + num(m.positions[3 * v + 1]) + " " +
         num(m.positions[3 * v + 2]);
    if (extras && v % 3 == 0) s += " 1.0 0.5 0.25 0.125";  // w / colour values: ignored
    if (extras && v % 5 == 0) s += " # trailing comment";
    s += nl;
  }
  for (size_t v = 0; v < nv; ++v) s += "vt " + num(m.uvs[2 * v]) + " " + num(m.uvs[2 * v + 1]) + nl;
  for (size_t v = 0; v < nv; ++v) s += "vn 0 0 1" + nl;
  s += "g group" + nl + "s off" + nl + "usemtl red" + nl + nl + "   " + nl;
  for (const auto& f : m.faces) {
    s += "f";
    for (uint32_t v : f) {
      std::string i = relative ? std::to_string(int64_t(v) - int64_t(nv)) : std::to_string(v + 1);
      s += extras ? "  " : " ";
      switch (corner) {
        case Corner::Plain: s += i; break;
        case Corner::WithUv: s += i + "/" + i; break;
        case Corner::WithUvNormal: s += i + "/" + i + "/" + i; break;
        case Corner::WithNormal: s += i + "//" + i; break;
      }
    }
    s += nl;
  }
  s += "l 1 2" + nl;  // polylines are not faces
  return s;
}

}  // namespace

TEST_CASE("OBJ: every corner syntax, absolute and relative indices, LF and CRLF give the same mesh") {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    PolyMesh m = randomPolyMesh(seed);
    const std::vector<uint32_t> tris = fanTriangles(m);
    for (Corner c : {Corner::Plain, Corner::WithUv, Corner::WithUvNormal, Corner::WithNormal})
      for (int variant = 0; variant < 8; ++variant) {
        const bool relative = variant & 1, crlf = variant & 2, extras = variant & 4;
        CAPTURE(seed);
        CAPTURE(int(c));
        CAPTURE(variant);
        ReadResult r = readMesh(bytesOf(objText(m, c, relative, crlf, extras)));
        CHECK(r.format == MeshFormat::Obj);
        REQUIRE(r.mesh.positions.size() == m.positions.size());
        bool exact = true;
        for (size_t i = 0; i < m.positions.size(); ++i) exact &= sameBits(r.mesh.positions[i], m.positions[i]);
        CHECK(exact);
        CHECK(r.mesh.triangles == tris);
        const bool hasUv = c == Corner::WithUv || c == Corner::WithUvNormal;
        CHECK(r.mesh.uvs.empty() == !hasUv);
        if (hasUv) CHECK(r.mesh.uvs == m.uvs);
      }
  }
}

TEST_CASE("OBJ: uvs kept per vertex when each vertex has one vt (any vt order), per corner at a seam") {
  // vt listed in reverse order: vertex v uses vt (n - v).
  std::string s = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0.75 0.5\nvt 0.25 0.5\nvt 1 0\nvt 0 0\n"
                  "f 1/4 2/3 3/2\nf 2/3 4/1 3/2\n";
  ReadResult r = readMesh(bytesOf(s));
  REQUIRE(r.mesh.uvs.size() == 8);
  CHECK(r.mesh.uvs == std::vector<double>{0, 0, 1, 0, 0.25, 0.5, 0.75, 0.5});
  // Vertex 3 with two different vt: a seam. Positions stay shared, uvs per corner.
  std::string seam = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.5\n"
                     "f 1/1 2/2 3/3\nf 2/2 4/4 3/5\n";
  ReadResult r2 = readMesh(bytesOf(seam));
  CHECK(r2.mesh.uvs.empty());
  CHECK(r2.mesh.triangleCount() == 2);
  CHECK(r2.warnings.empty());
  REQUIRE(r2.mesh.attributes.size() == 1);
  CHECK(r2.mesh.attributes[0].name == "uv");
  CHECK(r2.mesh.attributes[0].perCorner);
  CHECK(r2.mesh.attributes[0].values == std::vector<double>{0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0.5, 0.5});
  // a face corner without vt: uvs dropped with a warning
  ReadResult r3 = readMesh(bytesOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n"));
  CHECK(r3.mesh.uvs.empty());
  CHECK(r3.mesh.attributes.empty());
  CHECK(r3.warnings.size() == 1);
  ReadOptions noUv;
  noUv.readUvs = false;
  CHECK(readMesh(bytesOf(s), noUv).mesh.uvs.empty());
}

TEST_CASE("a UTF-8 byte order mark before a text format is skipped") {
  ReadResult r = readMesh(bytesOf("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  CHECK(r.format == MeshFormat::Obj);
  CHECK(r.mesh.triangleCount() == 1);
  ReadResult r2 = readMesh(bytesOf("\xEF\xBB\xBFOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  CHECK(r2.format == MeshFormat::Off);
}

TEST_CASE("OBJ: degenerate faces are kept, polygons fan-triangulated") {
  ReadResult r = readMesh(bytesOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 1 2 3 1 2\n"));
  CHECK(r.mesh.triangles == std::vector<uint32_t>{0, 0, 1, 0, 1, 2, 0, 2, 0, 0, 0, 1});
}

TEST_CASE("OBJ: errors carry a code and the line") {
  auto codeOf = [](const std::string& text, std::string* msg = nullptr) {
    try {
      readMesh(bytesOf(text));
    } catch (const Error& e) {
      if (msg) *msg = e.what();
      CHECK(e.stage() == Stage::Read);
      return e.code();
    }
    return Code::Ok;
  };
  std::string msg;
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", &msg) == Code::ParseError);
  CHECK(msg.find("line 4") != std::string::npos);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\n# c\nv 0 1 abc\nf 1 2 3\n", &msg) == Code::ParseError);
  CHECK(msg.find("line 4") != std::string::npos);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", &msg) == Code::IndexOutOfRange);
  CHECK(msg.find("line 4") != std::string::npos);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n") == Code::IndexOutOfRange);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -1 -2\n") == Code::IndexOutOfRange);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2/1 3/1\nvt 0 0\n") == Code::IndexOutOfRange);
  CHECK(codeOf("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", &msg) == Code::NonFiniteCoordinate);
  CHECK(msg.find("line 2") != std::string::npos);
  CHECK(codeOf("v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n") == Code::NonFiniteCoordinate);
  CHECK(codeOf("v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n") == Code::NonFiniteCoordinate);
  CHECK(codeOf("v 0 0 0\nv 1 0 0\nv 0 1 0\n") == Code::EmptyMesh);
  CHECK(codeOf("# nothing\n") == Code::ParseError);  // not recognisable as any format
  ReadOptions asObj;
  asObj.fileName = "x.obj";
  try {
    readMesh(bytesOf("# nothing\n"), asObj);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.code() == Code::EmptyMesh);
    CHECK(std::string(e.what()).find("x.obj") != std::string::npos);
  }
}
