// OFF reader: header variants, comments, colours/normals/texture values, polygons, and errors.
#include <doctest/doctest.h>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

// OFF text for m with the given header keyword; extra per-vertex values follow the keyword's
// letters (ST: 2, C: 4, N: 3). Variants: counts on the header line, comments, per-face colours.
std::string offText(const PolyMesh& m, const std::string& keyword, bool countsOnHeaderLine, bool comments,
                    bool faceColours, bool edgeCount = true) {
  const size_t nv = m.positions.size() / 3;
  std::string s;
  if (comments) s += "# a comment before the header\n\n";
  s += keyword;
  s += countsOnHeaderLine ? " " : (comments ? "  # keyword\n# between\n" : "\n");
  s += std::to_string(nv) + " " + std::to_string(m.faces.size()) + (edgeCount ? " 0" : "") + "\n";
  const bool st = keyword.find("ST") != std::string::npos;
  const bool c = keyword.find('C') != std::string::npos;
  const bool n = keyword.find('N') != std::string::npos;
  for (size_t v = 0; v < nv; ++v) {
    s += num(m.positions[3 * v]) + " " + num(m.positions[3 * v + 1]) + "  " + num(m.positions[3 * v + 2]);
    if (n) s += " 0 0 1";
    if (c) s += v % 2 ? " 0.5 0.5 0.5 1" : " 255 0 0";  // rgba floats or rgb ints
    if (st) s += " 0.25 0.75";
    if (comments && v % 7 == 0) s += " # vertex comment";
    s += "\n";
    if (comments && v % 11 == 0) s += "# a comment line\n";
  }
  for (const auto& f : m.faces) {
    s += std::to_string(f.size());
    for (uint32_t i : f) s += " " + std::to_string(i);
    if (faceColours) s += " 0.1 0.2 0.3 1.0";
    s += "\n";
  }
  return s;
}

Code codeOf(const std::string& text, std::string* msg = nullptr) {
  try {
    readMesh(bytesOf(text));
  } catch (const Error& e) {
    if (msg) *msg = e.what();
    return e.code();
  }
  return Code::Ok;
}

}  // namespace

TEST_CASE("OFF: header variants, comments and skipped values give the same mesh") {
  for (uint64_t seed = 10; seed < 14; ++seed) {
    PolyMesh m = randomPolyMesh(seed);
    const std::vector<uint32_t> tris = fanTriangles(m);
    for (const char* kw : {"OFF", "COFF", "NOFF", "STOFF", "CNOFF", "STCNOFF"})
      for (int variant = 0; variant < 16; ++variant) {
        CAPTURE(seed);
        CAPTURE(kw);
        CAPTURE(variant);
        ReadResult r = readMesh(bytesOf(offText(m, kw, variant & 1, variant & 2, variant & 4, variant & 8)));
        CHECK(r.format == MeshFormat::Off);
        REQUIRE(r.mesh.positions.size() == m.positions.size());
        bool exact = true;
        for (size_t i = 0; i < m.positions.size(); ++i) exact &= sameBits(r.mesh.positions[i], m.positions[i]);
        CHECK(exact);
        CHECK(r.mesh.triangles == tris);
      }
  }
}

TEST_CASE("OFF: 4OFF divides by w, nOFF reads the dimension, a headerless file needs a name") {
  ReadResult r = readMesh(bytesOf("4OFF\n3 1 0\n2 0 0 2\n0 4 0 2\n0 0 8 4\n3 0 1 2\n"));
  CHECK(r.mesh.positions == std::vector<double>{1, 0, 0, 0, 2, 0, 0, 0, 2});
  ReadResult r2 = readMesh(bytesOf("nOFF 2\n3 1 0\n1 0\n0 1\n0 0\n3 0 1 2\n"));
  CHECK(r2.mesh.positions == std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 0});
  ReadResult r3 = readMesh(bytesOf("nOFF\n3\n3 1 0\n1 0 5\n0 1 5\n0 0 5\n3 0 1 2\n"));
  CHECK(r3.mesh.positions == std::vector<double>{1, 0, 5, 0, 1, 5, 0, 0, 5});
  const std::string headerless = "3 1 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";
  CHECK(codeOf(headerless) == Code::ParseError);
  ReadOptions o;
  o.fileName = "mesh.off";
  CHECK(readMesh(bytesOf(headerless), o).mesh.triangleCount() == 1);
}

TEST_CASE("OFF: errors carry a code and the line") {
  std::string msg;
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", &msg) == Code::ParseError);
  CHECK(msg.find("line 6") != std::string::npos);
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", &msg) == Code::IndexOutOfRange);
  CHECK(msg.find("line 6") != std::string::npos);
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n") == Code::IndexOutOfRange);
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", &msg) == Code::NonFiniteCoordinate);
  CHECK(msg.find("line 4") != std::string::npos);
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n") == Code::ParseError);
  // Truncated: a count that cannot fit in the bytes at all is TooLarge, else a ParseError at the end.
  CHECK(codeOf("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") == Code::TooLarge);
  CHECK(codeOf("OFF\n3 2 0\n0.000 0.000 0.000\n1.000 0 0\n0 1 0\n3 0 1 2\n", &msg) == Code::ParseError);
  CHECK(msg.find("end of file") != std::string::npos);
  CHECK(codeOf("OFF\n4000000000 1 0\n0 0 0\n") == Code::TooLarge);
  CHECK(codeOf("OFF\n3 999999999999 0\n0 0 0\n") == Code::TooLarge);
  CHECK(codeOf("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n") == Code::ParseError);
  CHECK(codeOf("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n") == Code::EmptyMesh);
  CHECK(codeOf("OFF\n-3 1 0\n") == Code::ParseError);
}
