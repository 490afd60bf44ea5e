// Replays every input the remesh fuzzer flagged (tests/data/fuzz-regressions-remesh, filled by
// tests/fuzz/run.sh), decoded as the harness decodes it: remesh must return a documented status,
// or a valid mesh within the limits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "remesh/fuzz_remesh_input.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {
// Remesh the decoded bytes and check the harness's properties.
void checkReplay(const std::vector<uint8_t>& bytes) {
  fuzz::RemeshInput in = fuzz::decodeRemeshInput(bytes.data(), bytes.size());
  RemeshResult r = remesh(in.mesh, in.options);
  if (!r.status.ok()) {
    CHECK(std::string(codeName(r.status.code)) != "Unknown");
    CHECK(!r.status.message.empty());
    CHECK(r.mesh.triangleCount() == 0);
    return;
  }
  const MeshBuffers& m = r.mesh;
  CHECK(m.triangleCount() > 0);
  CHECK(m.triangleCount() <= in.options.maxTriangles);
  CHECK(std::all_of(m.positions.begin(), m.positions.end(), [](double x) { return std::isfinite(x); }));
  CHECK(std::all_of(m.triangles.begin(), m.triangles.end(), [&](uint32_t t) { return t < m.vertexCount(); }));
}
}  // namespace

TEST_CASE("fuzz regressions (remesh): every flagged input gives a status or a valid mesh") {
  std::filesystem::path dir = std::filesystem::path(CONFORMESH_TESTS_DIR) / "data" / "fuzz-regressions-remesh";
  REQUIRE(std::filesystem::is_directory(dir));
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    CAPTURE(file.filename().string());
    std::ifstream f(file, std::ios::binary);
    checkReplay(std::vector<uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>()));
  }
}

TEST_CASE("fuzz input decoding: seeds decode to the meshes the harness documents") {
  const uint8_t flat[] = {0x20, 0x00, 0x01, 0x01};
  fuzz::RemeshInput a = fuzz::decodeRemeshInput(flat, sizeof flat);
  CHECK(a.mesh.vertexCount() == 9);
  CHECK(a.mesh.triangleCount() == 8);
  checkReplay({flat, flat + sizeof flat});
  const uint8_t tetra[] = {0x30, 0x01, 0x01, 0x00, 0x01, 0x04, 0x10, 0x03, 0x00, 0x02, 0x01, 0x00, 0x01, 0x03, 0x01, 0x02, 0x03, 0x02, 0x00, 0x03};
  fuzz::RemeshInput b = fuzz::decodeRemeshInput(tetra, sizeof tetra);
  CHECK(b.mesh.vertexCount() == 4);
  CHECK(b.mesh.triangleCount() == 4);
  checkReplay({tetra, tetra + sizeof tetra});
}
