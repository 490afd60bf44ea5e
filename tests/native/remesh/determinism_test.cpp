#include <doctest/doctest.h>

#include <cstring>
#include <string>

#include "features/test_shapes.h"
#include "mesh/mesh_io.h"
#include "mesh/mesh_io_test_util.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {
// Two runs with the same input and options: the same bits in every position and index.
void checkSameOutputTwice(const MeshBuffers& in, const RemeshOptions& o) {
  RemeshResult a = remesh(in, o), b = remesh(in, o);
  REQUIRE_MESSAGE(a.status.ok(), a.status.message);
  REQUIRE(b.status.ok());
  REQUIRE(a.mesh.positions.size() == b.mesh.positions.size());
  REQUIRE(a.mesh.triangles.size() == b.mesh.triangles.size());
  CHECK(std::memcmp(a.mesh.positions.data(), b.mesh.positions.data(), a.mesh.positions.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(a.mesh.triangles.data(), b.mesh.triangles.data(), a.mesh.triangles.size() * sizeof(uint32_t)) == 0);
  CHECK(a.report.minAngle == b.report.minAngle);
}
}  // namespace

TEST_CASE("remesh determinism: the same input and options give bit-identical output (cube)") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.computeHausdorff = false;
  checkSameOutputTwice(testshapes::cube(4), o);
}

TEST_CASE("remesh determinism: the same input and options give bit-identical output (fandisk)") {
  std::vector<uint8_t> bytes = test::readFile(std::string(CONFORMESH_DATA_DIR) + "/fandisk.off");
  REQUIRE(!bytes.empty());
  ReadOptions ro;
  ro.fileName = "fandisk.off";
  MeshBuffers in = readMesh(bytes, ro).mesh;
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.03;
  o.computeHausdorff = false;
  checkSameOutputTwice(in, o);
}
