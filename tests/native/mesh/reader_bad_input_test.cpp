// The readers' bad-input corpus. Built twice: in conformesh_tests and, with AddressSanitizer and
// UndefinedBehaviorSanitizer, in conformesh_tests_asan. Every input yields its documented code;
// random and mutated inputs yield some Error (never a crash, a hang, or a huge allocation).
#include <doctest/doctest.h>

#include "mesh/mesh_attributes.h"
#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

const MeshFormat kForced[] = {MeshFormat::Auto,     MeshFormat::Obj,         MeshFormat::Off,
                              MeshFormat::StlAscii, MeshFormat::StlBinary,   MeshFormat::PlyAscii,
                              MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE};

// Code of reading `bytes` (Ok if it reads). Any exception other than conformesh::Error fails.
Code codeOf(const uint8_t* data, size_t size, MeshFormat f = MeshFormat::Auto, std::string* msg = nullptr) {
  ReadOptions o;
  o.format = f;
  try {
    ReadResult r = readMesh(data, size, o);
    // What does read is well formed.
    CHECK(r.mesh.positions.size() % 3 == 0);
    CHECK(r.mesh.triangles.size() % 3 == 0);
    CHECK(r.mesh.triangleCount() > 0);
    for (uint32_t t : r.mesh.triangles) CHECK(t < r.mesh.vertexCount());
    for (double x : r.mesh.positions) CHECK(std::isfinite(x));
    CHECK_NOTHROW(checkAttributes(r.mesh, Stage::Read));  // attribute sizes match, values finite
  } catch (const Error& e) {
    if (msg) *msg = e.what();
    CHECK(e.stage() == Stage::Read);
    return e.code();
  }
  return Code::Ok;
}
Code codeOf(const std::vector<uint8_t>& b, MeshFormat f = MeshFormat::Auto, std::string* msg = nullptr) {
  return codeOf(b.data(), b.size(), f, msg);
}

std::vector<uint8_t> randomBytes(size_t n, uint64_t seed) {
  Rng r(seed);
  std::vector<uint8_t> b(n);
  for (size_t i = 0; i < n; i += 8) {
    uint64_t v = r.next();
    for (size_t k = 0; k < 8 && i + k < n; ++k) b[i + k] = uint8_t(v >> (8 * k));
  }
  return b;
}

// Small valid files of each format, for mutation.
std::vector<std::vector<uint8_t>> seeds() {
  MeshBuffers m = toBuffers(randomPolyMesh(90, 12, 10), true);
  std::vector<std::vector<uint8_t>> s;
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::StlAscii, MeshFormat::StlBinary,
                       MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE})
    s.push_back(writeMesh(m, f));
  // with attributes: uvs per corner (a seam at every vertex), normals per corner, a colour and a
  // scalar per vertex (OBJ vt/vn, PLY properties and the texcoord face list)
  m.uvs.clear();
  MeshAttribute uv{"uv", 2, true, {}}, normal{"normal", 3, true, {}}, color{"color", 3, false, {}}, q{"quality", 1, false, {}};
  for (size_t c = 0; c < m.triangles.size(); ++c) uv.values.insert(uv.values.end(), {double(c % 7) / 7, double(c % 5) / 5}),
                                                  normal.values.insert(normal.values.end(), {0.0, double(c % 2), 1.0});
  for (size_t v = 0; v < m.vertexCount(); ++v) color.values.insert(color.values.end(), {double(v % 3) / 2, 0.5, 1.0}), q.values.push_back(double(v));
  m.attributes = {uv, normal, color, q};
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE})
    s.push_back(writeMesh(m, f));
  return s;
}

}  // namespace

TEST_CASE("bad input: empty file -> EmptyMesh, whatever the format") {
  for (MeshFormat f : kForced) {
    CAPTURE(formatName(f));
    CHECK(codeOf(nullptr, 0, f) == Code::EmptyMesh);
  }
  CHECK(codeOf(bytesOf("   \n\n")) == Code::ParseError);  // nothing recognisable
}

TEST_CASE("bad input: truncated binary STL -> ParseError with the byte offset") {
  std::vector<uint8_t> stl = seeds()[3];
  for (size_t cut : {size_t(1), size_t(13), size_t(49), size_t(50), stl.size() - 84, stl.size() - 1}) {
    std::vector<uint8_t> t(stl.begin(), stl.end() - long(cut));
    std::string msg;
    CAPTURE(cut);
    CHECK(codeOf(t, MeshFormat::StlBinary, &msg) == Code::ParseError);
    CHECK(msg.find("byte offset") != std::string::npos);
  }
  // Header claims 4e9 triangles in a 200-byte file.
  std::vector<uint8_t> claim(stl.begin(), stl.begin() + 200);
  claim[80] = claim[81] = claim[82] = claim[83] = 0xEE;
  CHECK(codeOf(claim, MeshFormat::StlBinary) == Code::ParseError);
}

TEST_CASE("bad input: PLY with a bad header -> ParseError; absurd counts -> TooLarge") {
  CHECK(codeOf(bytesOf("ply\nformat ascii 1.0\nelement vertex three\nend_header\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("ply\nformat ascii 1.0\nelement vertex 3\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty list uchar float x\n"
                       "property floaty\nend_header\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("ply\nformat binary_big_endian 1.0\nelement vertex 4000000000\nproperty double x\n"
                       "property double y\nproperty double z\nelement face 4000000000\n"
                       "property list uchar uint vertex_indices\nend_header\n")) == Code::TooLarge);
  CHECK(codeOf(bytesOf("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n"
                       "000000000000000000000000000000000000\xff\xff\xff\xff")) == Code::ParseError);
  // An element without properties costs nothing, whatever its count: no 4e9-iteration loop.
  std::string triangle = "ply\nformat binary_little_endian 1.0\nelement junk 4000000000\nelement vertex 3\n"
                         "property uchar x\nproperty uchar y\nproperty uchar z\nelement face 1\n"
                         "property list uchar uchar vertex_indices\nend_header\n";
  triangle += std::string("\0\0\0\1\0\0\0\1\0\3\0\1\2", 13);
  CHECK(codeOf(bytesOf(triangle)) == Code::Ok);
}

TEST_CASE("bad input: OFF counts near 2^62 do not overflow the size check") {
  CHECK(codeOf(bytesOf("OFF\n3 2305843009213693952 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")) == Code::TooLarge);
  CHECK(codeOf(bytesOf("OFF\n4611686018427387904 1 0\n0 0 0\n")) == Code::TooLarge);
  CHECK(codeOf(bytesOf("OFF\n3 9999999999999999999999 0\n")) == Code::ParseError);
}

TEST_CASE("bad input: OBJ index out of range, NaN coordinates") {
  CHECK(codeOf(bytesOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")) == Code::IndexOutOfRange);
  CHECK(codeOf(bytesOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n")) == Code::ParseError);
  CHECK(codeOf(bytesOf("v 0 0 0\nv 1 0 NaN\nv 0 1 0\nf 1 2 3\n")) == Code::NonFiniteCoordinate);
  CHECK(codeOf(bytesOf("OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n")) == Code::NonFiniteCoordinate);
  std::vector<uint8_t> stl = seeds()[3];
  const float nan = std::nanf("");
  std::memcpy(&stl[84 + 12 + 4], &nan, 4);
  CHECK(codeOf(stl) == Code::NonFiniteCoordinate);
}

TEST_CASE("bad input: 10 MB of random bytes -> ParseError; forced formats -> an Error, fast") {
  std::vector<uint8_t> junk = randomBytes(10u << 20, 12345);
  CHECK(codeOf(junk) == Code::ParseError);
  for (MeshFormat f : kForced) {
    CAPTURE(formatName(f));
    Code c = codeOf(junk, f);
    CHECK(c != Code::Ok);
  }
  // Random bytes behind each format's magic.
  for (const char* magic : {"ply\nformat binary_little_endian 1.0\n", "ply\nformat ascii 1.0\n", "OFF\n", "solid x\n",
                            "v 1 2 3\n"}) {
    CAPTURE(magic);
    std::vector<uint8_t> b = bytesOf(magic);
    std::vector<uint8_t> tail = randomBytes(1u << 16, 7);
    b.insert(b.end(), tail.begin(), tail.end());
    CHECK(codeOf(b) != Code::Ok);
  }
}

TEST_CASE("bad input: mutated and truncated small files never crash") {
  std::vector<std::vector<uint8_t>> files = seeds();
  Rng r(99);
  int errors = 0, reads = 0;
  for (const std::vector<uint8_t>& f : files) {
    for (size_t cut = 0; cut < f.size(); cut += 1 + f.size() / 97) {
      std::vector<uint8_t> t(f.begin(), f.begin() + long(cut));
      (codeOf(t) == Code::Ok ? reads : errors)++;
    }
    for (int trial = 0; trial < 150; ++trial) {
      std::vector<uint8_t> m = f;
      const int flips = 1 + int(r.below(4));
      for (int k = 0; k < flips; ++k) {
        const size_t at = r.below(uint32_t(m.size()));
        switch (r.below(3)) {
          case 0: m[at] = uint8_t(r.next()); break;
          case 1: m[at] = uint8_t("0123456789-.e \n/#"[r.below(17)]); break;
          default: m[at] = 0xFF; break;
        }
      }
      (codeOf(m) == Code::Ok ? reads : errors)++;
    }
  }
  CHECK(errors > 0);
  CHECK(reads > 0);
}
