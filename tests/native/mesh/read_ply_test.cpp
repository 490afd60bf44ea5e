// PLY reader: ascii, binary little and big endian; float/double positions among other
// properties; every list count / index type; extra elements and properties; errors.
#include <doctest/doctest.h>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

enum class Enc { Ascii, LE, BE };

struct Layout {
  Enc enc = Enc::LE;
  const char* coordType = "double";  // float or double
  const char* countType = "uchar";
  const char* indexType = "int";
  const char* indexName = "vertex_indices";
  bool extras = false;  // extra vertex/face properties, an extra element, comments, obj_info
  bool uvs = false;
};

size_t sizeOf(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

// Writes values of a PLY type, in the layout's encoding.
struct Emitter {
  Enc enc;
  std::string out;
  void value(const std::string& type, double v) {
    if (enc == Enc::Ascii) {
      out += (type == "float" || type == "double") ? num(type == "float" ? double(float(v)) : v)
                                                   : std::to_string(int64_t(v));
      out += ' ';
      return;
    }
    uint8_t b[8];
    const size_t n = sizeOf(type);
    if (type == "double") {
      std::memcpy(b, &v, 8);
    } else if (type == "float") {
      float f = float(v);
      std::memcpy(b, &f, 4);
    } else {
      int64_t i = int64_t(v);
      for (size_t k = 0; k < n; ++k) b[k] = uint8_t(uint64_t(i) >> (8 * k));
    }
    for (size_t k = 0; k < n; ++k) out += char(enc == Enc::BE ? b[n - 1 - k] : b[k]);
  }
  void endItem() {
    if (enc == Enc::Ascii) out += '\n';
  }
};

std::string plyText(const PolyMesh& m, const Layout& L) {
  const size_t nv = m.positions.size() / 3;
  std::string h = "ply\n";
  h += std::string("format ") + (L.enc == Enc::Ascii ? "ascii" : L.enc == Enc::LE ? "binary_little_endian" : "binary_big_endian") + " 1.0\n";
  if (L.extras) h += "comment made by a test\nobj_info nothing\n";
  if (L.extras) h += "element material 2\nproperty uchar red\nproperty list uchar float weights\n";
  h += "element vertex " + std::to_string(nv) + "\n";
  if (L.extras) h += "property float nx\nproperty uchar alpha\n";
  h += std::string("property ") + L.coordType + " x\n";
  if (L.extras) h += "property list uchar int neighbours\n";
  h += std::string("property ") + L.coordType + " y\nproperty " + L.coordType + " z\n";
  if (L.uvs) h += "property double u\nproperty double v\n";
  if (L.extras) h += "property short quality\n";
  h += "element face " + std::to_string(m.faces.size()) + "\n";
  if (L.extras) h += "property uchar flags\n";
  h += std::string("property list ") + L.countType + " " + L.indexType + " " + L.indexName + "\n";
  if (L.extras) h += "property list uchar float texcoord\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n";
  h += "end_header\n";
  Emitter e{L.enc, h};
  if (L.extras) {
    for (int i = 0; i < 2; ++i) {
      e.value("uchar", 7);
      e.value("uchar", 2);
      e.value("float", 0.5);
      e.value("float", 0.25);
      e.endItem();
    }
  }
  for (size_t v = 0; v < nv; ++v) {
    if (L.extras) e.value("float", 1.5), e.value("uchar", 255);
    e.value(L.coordType, m.positions[3 * v]);
    if (L.extras) e.value("uchar", 2), e.value("int", 1), e.value("int", 2);
    e.value(L.coordType, m.positions[3 * v + 1]);
    e.value(L.coordType, m.positions[3 * v + 2]);
    if (L.uvs) e.value("double", m.uvs[2 * v]), e.value("double", m.uvs[2 * v + 1]);
    if (L.extras) e.value("short", -3);
    e.endItem();
  }
  for (const auto& f : m.faces) {
    if (L.extras) e.value("uchar", 1);
    e.value(L.countType, double(f.size()));
    for (uint32_t i : f) e.value(L.indexType, i);
    if (L.extras) e.value("uchar", 2), e.value("float", 0.5), e.value("float", 0.5);
    e.endItem();
  }
  if (L.extras) e.value("int", 0), e.value("int", 1), e.endItem();
  return e.out;
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

TEST_CASE("PLY: ascii / LE / BE, float and double, every list type, extra elements and properties") {
  PolyMesh m = randomPolyMesh(50, 100, 120);  // 100 vertices: indices fit in char
  const std::vector<uint32_t> tris = fanTriangles(m);
  int cases = 0;
  for (Enc enc : {Enc::Ascii, Enc::LE, Enc::BE})
    for (const char* coord : {"float", "double"})
      for (const char* count : {"uchar", "char", "short", "ushort", "int", "uint"})
        for (const char* index : {"int", "uint", "char", "uchar", "short", "ushort"})
          for (int variant = 0; variant < 2; ++variant) {
            Layout L;
            L.enc = enc;
            L.coordType = coord;
            L.countType = count;
            L.indexType = index;
            L.extras = variant;
            L.indexName = variant ? "vertex_index" : "vertex_indices";
            CAPTURE(int(enc));
            CAPTURE(coord);
            CAPTURE(count);
            CAPTURE(index);
            CAPTURE(variant);
            ReadResult r = readMesh(bytesOf(plyText(m, L)));
            CHECK(r.format == (enc == Enc::Ascii ? MeshFormat::PlyAscii
                               : enc == Enc::LE  ? MeshFormat::PlyBinaryLE
                                                 : MeshFormat::PlyBinaryBE));
            REQUIRE(r.mesh.positions.size() == m.positions.size());
            bool exact = true;
            for (size_t i = 0; i < m.positions.size(); ++i) {
              double want = std::string(coord) == "float" ? double(float(m.positions[i])) : m.positions[i];
              exact &= sameBits(r.mesh.positions[i], want);
            }
            CHECK(exact);
            CHECK(r.mesh.triangles == tris);
            CHECK(r.mesh.uvs.empty());
            ++cases;
          }
  CHECK(cases == 432);
}

TEST_CASE("PLY: u, v vertex properties become uvs") {
  PolyMesh m = randomPolyMesh(51);
  for (Enc enc : {Enc::Ascii, Enc::LE, Enc::BE}) {
    Layout L;
    L.enc = enc;
    L.uvs = true;
    ReadResult r = readMesh(bytesOf(plyText(m, L)));
    CHECK(r.mesh.uvs == m.uvs);
  }
}

TEST_CASE("PLY: errors") {
  PolyMesh m = randomPolyMesh(52);
  Layout L;
  std::string good = plyText(m, L);
  std::string msg;
  CHECK(codeOf(good) == Code::Ok);
  // Truncated body: byte offset.
  CHECK(codeOf(good.substr(0, good.size() - 5), &msg) == Code::ParseError);
  CHECK(msg.find("byte offset") != std::string::npos);
  // Header problems: line numbers.
  CHECK(codeOf("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty floot x\nend_header\n", &msg) ==
        Code::ParseError);
  CHECK(msg.find("line 4") != std::string::npos);
  CHECK(codeOf("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n") == Code::ParseError);
  CHECK(codeOf("ply\nformat zip 1.0\nend_header\n") == Code::ParseError);
  CHECK(codeOf("ply\nproperty float x\nend_header\n") == Code::ParseError);
  CHECK(codeOf("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\n"
               "property list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n") == Code::ParseError);
  // Counts that cannot fit: TooLarge, before allocating.
  CHECK(codeOf("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0123456789",
               &msg) == Code::TooLarge);
  CHECK(msg.find("line 3") != std::string::npos);
  CHECK(codeOf("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 99999999999\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
               "3 0 1 2\n") == Code::TooLarge);
  // Faces: < 3 corners, index out of range, NaN.
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK(codeOf(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") == Code::Ok);
  CHECK(codeOf(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", &msg) == Code::ParseError);
  CHECK(msg.find("line 13") != std::string::npos);
  CHECK(codeOf(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n") == Code::IndexOutOfRange);
  CHECK(codeOf(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n") == Code::IndexOutOfRange);
  CHECK(codeOf(head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n") == Code::NonFiniteCoordinate);
  CHECK(codeOf("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "end_header\n0 0 0\n1 0 0\n0 1 0\n") == Code::EmptyMesh);
}
