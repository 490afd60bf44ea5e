// Writers: write then read gives identical positions (bit for bit) and triangles for every
// writer; uvs through OBJ and PLY; binary STL exact for float-representable positions.
#include <doctest/doctest.h>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

const MeshFormat kAll[] = {MeshFormat::Obj,      MeshFormat::Off,         MeshFormat::StlAscii,   MeshFormat::StlBinary,
                           MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE};

bool bitsEqual(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!sameBits(a[i] + 0.0, b[i] + 0.0)) return false;
  return true;
}

// Per triangle corner, its position: compares meshes whatever the vertex numbering.
std::vector<double> cornerPositions(const MeshBuffers& m) {
  std::vector<double> c;
  for (uint32_t v : m.triangles) c.insert(c.end(), &m.positions[3 * size_t(v)], &m.positions[3 * size_t(v)] + 3);
  return c;
}

}  // namespace

TEST_CASE("round trip through every writer is exact (binary STL: for float inputs)") {
  for (uint64_t seed = 60; seed < 64; ++seed) {
    MeshBuffers m = toBuffers(randomPolyMesh(seed), true);
    m.positions[0] = -0.0;
    m.positions[1] = 1e-310;  // subnormal
    m.positions[2] = 1.7976931348623157e308;
    MeshBuffers mf = m;
    for (double& x : mf.positions) x = std::isfinite(float(x)) ? double(float(x)) : 1.0;
    for (MeshFormat f : kAll) {
      CAPTURE(formatName(f));
      CAPTURE(seed);
      const MeshBuffers& in = f == MeshFormat::StlBinary ? mf : m;
      std::vector<uint8_t> bytes = writeMesh(in, f);
      ReadResult r = readMesh(bytes);  // detected from the content
      CHECK(r.format == f);
      // randomPolyMesh uses vertices in index order first: STL's first-appearance order agrees.
      CHECK(bitsEqual(r.mesh.positions, in.positions));
      CHECK(r.mesh.triangles == in.triangles);
      const bool uvFormat = f == MeshFormat::Obj || f == MeshFormat::PlyAscii || f == MeshFormat::PlyBinaryLE ||
                            f == MeshFormat::PlyBinaryBE;
      if (uvFormat) CHECK(bitsEqual(r.mesh.uvs, in.uvs));
      else CHECK(r.mesh.uvs.empty());
      WriteOptions noUv;
      noUv.writeUvs = false;
      CHECK(readMesh(writeMesh(in, f, noUv)).mesh.uvs.empty());
    }
    // Binary STL with double inputs: every corner comes back as the float nearest to it.
    m.positions[2] = 12345.678;  // in float range
    ReadResult r = readMesh(writeMesh(m, MeshFormat::StlBinary));
    std::vector<double> want = cornerPositions(m);
    for (double& x : want) x = double(float(x));
    CHECK(bitsEqual(cornerPositions(r.mesh), want));
  }
}

TEST_CASE("round trip of a real mesh through every writer keeps every corner position") {
  std::vector<uint8_t> bytes = readFile(std::string(CONFORMESH_DATA_DIR) + "/spot.obj");
  REQUIRE(!bytes.empty());
  MeshBuffers m = readMesh(bytes).mesh;
  for (MeshFormat f : kAll) {
    CAPTURE(formatName(f));
    MeshBuffers back = readMesh(writeMesh(m, f)).mesh;
    std::vector<double> want = cornerPositions(m);
    if (f == MeshFormat::StlBinary)
      for (double& x : want) x = double(float(x));
    CHECK(bitsEqual(cornerPositions(back), want));
    CHECK(back.triangleCount() == m.triangleCount());
  }
}

TEST_CASE("writers reject bad buffers") {
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  m.triangles = {0, 1, 2};
  auto codeOf = [](const MeshBuffers& b, MeshFormat f) {
    try {
      writeMesh(b, f);
    } catch (const Error& e) {
      CHECK(e.stage() == Stage::Write);
      return e.code();
    }
    return Code::Ok;
  };
  CHECK(codeOf(m, MeshFormat::Auto) == Code::InvalidArgument);
  MeshBuffers bad = m;
  bad.triangles[2] = 3;
  CHECK(codeOf(bad, MeshFormat::Obj) == Code::IndexOutOfRange);
  bad = m;
  bad.positions[4] = std::nan("");
  CHECK(codeOf(bad, MeshFormat::Off) == Code::NonFiniteCoordinate);
  bad = m;
  bad.positions[4] = 1e300;  // finite double, infinite float
  CHECK(codeOf(bad, MeshFormat::StlBinary) == Code::NonFiniteCoordinate);
  CHECK(codeOf(bad, MeshFormat::StlAscii) == Code::Ok);
  bad = m;
  bad.uvs = {0, 0};
  CHECK(codeOf(bad, MeshFormat::Obj) == Code::InvalidArgument);
  bad = m;
  bad.positions.pop_back();
  CHECK(codeOf(bad, MeshFormat::PlyBinaryLE) == Code::InvalidArgument);
}

TEST_CASE("format names and extensions") {
  for (MeshFormat f : kAll) CHECK(formatFromName(formatName(f)) == f);
  CHECK(formatFromName("dir.v2/Bunny.OBJ") == MeshFormat::Obj);
  CHECK(formatFromName(".stl") == MeshFormat::StlBinary);
  CHECK(formatFromName("PLY") == MeshFormat::PlyBinaryLE);
  CHECK(formatFromName("x.off") == MeshFormat::Off);
  CHECK(formatFromName("a.b/noext") == MeshFormat::Auto);
  CHECK(formatFromName("mesh.gltf") == MeshFormat::Auto);
}
