// STL readers: binary (also with a header that begins with "solid"), ascii variants, the exact
// weld (first-appearance order, -0 == +0) and errors with byte offsets / lines.
#include <doctest/doctest.h>

#include <map>
#include <tuple>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

using Key = std::tuple<double, double, double>;

// Expected exact weld, computed independently: std::map on the coordinates, first appearance.
void expectedWeld(const std::vector<double>& soup, std::vector<double>& pos, std::vector<uint32_t>& tris) {
  std::map<Key, uint32_t> index;
  for (size_t c = 0; c < soup.size() / 3; ++c) {
    Key k{soup[3 * c] + 0.0, soup[3 * c + 1] + 0.0, soup[3 * c + 2] + 0.0};  // + 0.0: -0 -> +0
    auto it = index.find(k);
    if (it == index.end()) {
      it = index.emplace(k, uint32_t(pos.size() / 3)).first;
      pos.insert(pos.end(), &soup[3 * c], &soup[3 * c] + 3);
    }
    tris.push_back(it->second);
  }
}

// Triangle soup of a random polygon mesh, coordinates rounded to float.
std::vector<double> floatSoup(uint64_t seed) {
  PolyMesh m = randomPolyMesh(seed);
  std::vector<double> soup;
  for (uint32_t v : fanTriangles(m))
    for (int k = 0; k < 3; ++k) soup.push_back(double(float(m.positions[3 * v + k])));
  return soup;
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

std::vector<uint8_t> binaryStl(const std::vector<double>& soup, const std::string& header) {
  std::vector<uint8_t> out(80, ' ');
  std::memcpy(out.data(), header.data(), std::min<size_t>(80, header.size()));
  const size_t n = soup.size() / 9;
  put32(out, uint32_t(n));
  for (size_t t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) put32(out, 0);  // normal: ignored by the reader
    for (int k = 0; k < 9; ++k) {
      float f = float(soup[9 * t + k]);
      uint32_t b;
      std::memcpy(&b, &f, 4);
      put32(out, b);
    }
    out.push_back(0);
    out.push_back(0);
  }
  return out;
}

Code codeOf(const std::vector<uint8_t>& bytes, std::string* msg = nullptr, const ReadOptions& o = {}) {
  try {
    readMesh(bytes, o);
  } catch (const Error& e) {
    if (msg) *msg = e.what();
    return e.code();
  }
  return Code::Ok;
}

}  // namespace

TEST_CASE("binary STL: exact weld in first-appearance order, also when the header says 'solid'") {
  for (uint64_t seed = 20; seed < 26; ++seed) {
    std::vector<double> soup = floatSoup(seed);
    soup[0] = -0.0;  // -0 and +0 weld
    soup[3] = 0.0;
    std::vector<double> pos;
    std::vector<uint32_t> tris;
    expectedWeld(soup, pos, tris);
    for (const char* header : {"binary from a test", "solid but binary", ""}) {
      CAPTURE(header);
      ReadResult r = readMesh(binaryStl(soup, header));
      CHECK(r.format == MeshFormat::StlBinary);
      CHECK(r.mesh.positions == pos);
      CHECK(r.mesh.triangles == tris);
    }
  }
}

TEST_CASE("ascii STL: case, spacing, CRLF, several solids, polygon loops") {
  std::vector<double> soup = floatSoup(30);
  for (double& c : soup) c = c * 3.0 + 1e-300;  // not float-representable: ascii keeps doubles
  std::vector<double> pos;
  std::vector<uint32_t> tris;
  expectedWeld(soup, pos, tris);
  for (int variant = 0; variant < 8; ++variant) {
    const bool upper = variant & 1, crlf = variant & 2, twoSolids = variant & 4;
    const std::string nl = crlf ? "\r\n" : "\n";
    auto kw = [&](std::string w) {
      if (upper)
        for (char& c : w) c = char(std::toupper(static_cast<unsigned char>(c)));
      return w;
    };
    std::string s = kw("solid") + " name with spaces" + nl;
    for (size_t t = 0; t < soup.size() / 9; ++t) {
      if (twoSolids && t == soup.size() / 18) s += kw("endsolid") + " a" + nl + kw("solid") + " b" + nl;
      s += "  " + kw("facet normal") + " 0 0 1" + nl + "\t" + kw("outer loop") + nl;
      for (int c = 0; c < 3; ++c)
        s += "   " + kw("vertex") + "  " + num(soup[9 * t + 3 * c]) + " " + num(soup[9 * t + 3 * c + 1]) + "\t" +
             num(soup[9 * t + 3 * c + 2]) + nl;
      s += "  " + kw("endloop") + nl + kw("endfacet") + nl;
    }
    s += kw("endsolid") + nl;
    CAPTURE(variant);
    ReadResult r = readMesh(bytesOf(s));
    CHECK(r.format == MeshFormat::StlAscii);
    CHECK(r.mesh.positions == pos);
    CHECK(r.mesh.triangles == tris);
    CHECK(r.warnings.empty());
  }
  // A quad loop is fan-triangulated.
  ReadResult q = readMesh(bytesOf("solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                  "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n"));
  CHECK(q.mesh.triangles == std::vector<uint32_t>{0, 1, 2, 0, 2, 3});
}

TEST_CASE("STL errors: truncation, size mismatch, non-finite values, bad ascii") {
  std::vector<uint8_t> good = binaryStl(floatSoup(40), "solid looks ascii");
  std::string msg;
  std::vector<uint8_t> cut(good.begin(), good.end() - 30);
  ReadOptions asStl;
  asStl.fileName = "part.stl";
  // Starts with "solid" and the size does not match: read as ascii, which fails on binary bytes.
  CHECK(codeOf(cut) == Code::ParseError);
  CHECK(codeOf(cut, &msg, asStl) == Code::ParseError);
  std::vector<uint8_t> cut2 = binaryStl(floatSoup(40), "plain header");
  cut2.resize(cut2.size() - 30);
  CHECK(codeOf(cut2, &msg, asStl) == Code::ParseError);
  CHECK(msg.find("byte offset") != std::string::npos);
  CHECK(msg.find("part.stl") != std::string::npos);
  std::vector<uint8_t> tiny(50, 0);
  CHECK(codeOf(tiny, &msg, asStl) == Code::ParseError);
  // Trailing bytes: accepted with a warning only when the format is given.
  std::vector<uint8_t> padded = binaryStl(floatSoup(41), "x");
  padded.resize(padded.size() + 7, 0);
  ReadResult r = readMesh(padded, asStl);
  CHECK(r.warnings.size() == 1);
  CHECK(codeOf(padded) == Code::ParseError);
  // NaN coordinate: its byte offset.
  std::vector<double> soup = floatSoup(42);
  soup[4] = std::nan("");
  CHECK(codeOf(binaryStl(soup, "x"), &msg) == Code::NonFiniteCoordinate);
  CHECK(msg.find("byte offset 112") != std::string::npos);  // 84 + 12 + 4 * 4
  CHECK(codeOf(binaryStl({}, "x")) == Code::EmptyMesh);
  CHECK(codeOf(bytesOf("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                       "endfacet\nendsolid\n"),
               &msg) == Code::ParseError);
  CHECK(msg.find("line 3") != std::string::npos);
  CHECK(codeOf(bytesOf("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 inf 0\n"
                       "endloop\nendfacet\nendsolid\n"),
               &msg) == Code::NonFiniteCoordinate);
  CHECK(msg.find("line 6") != std::string::npos);
  CHECK(codeOf(bytesOf("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nbanana\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("solid x\nendsolid x\n")) == Code::EmptyMesh);
}
