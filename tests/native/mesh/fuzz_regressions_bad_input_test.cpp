// Replays every input the fuzzers ever flagged (tests/data/fuzz-regressions, filled by
// tests/fuzz/run.sh) through every reader: each must come back as a valid mesh or a
// conformesh::Error with a documented code — never a crash, a sanitizer report (this file is also
// compiled into the ASan/UBSan test binary), another exception, or InternalError.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mesh/mesh_io.h"

using namespace conformesh;

namespace {

std::vector<std::filesystem::path> regressionInputs() {
  std::vector<std::filesystem::path> files;
  std::filesystem::path dir = std::filesystem::path(CONFORMESH_TESTS_DIR) / "data" / "fuzz-regressions";
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("fuzz regressions: every flagged input reads cleanly with every format") {
  std::filesystem::path dir = std::filesystem::path(CONFORMESH_TESTS_DIR) / "data" / "fuzz-regressions";
  REQUIRE(std::filesystem::is_directory(dir));
  const MeshFormat formats[] = {MeshFormat::Auto,     MeshFormat::Obj,         MeshFormat::Off,
                                MeshFormat::StlAscii, MeshFormat::StlBinary,   MeshFormat::PlyAscii,
                                MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE};
  for (const auto& file : regressionInputs()) {
    std::ifstream in(file, std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (MeshFormat f : formats) {
      CAPTURE(file.filename().string());
      CAPTURE(formatName(f));
      ReadOptions opt;
      opt.format = f;
      try {
        ReadResult r = readMesh(bytes, opt);
        const MeshBuffers& m = r.mesh;
        CHECK(m.triangleCount() > 0);
        CHECK(std::all_of(m.positions.begin(), m.positions.end(), [](double x) { return std::isfinite(x); }));
        CHECK(std::all_of(m.triangles.begin(), m.triangles.end(), [&](uint32_t t) { return t < m.vertexCount(); }));
      } catch (const Error& e) {
        CHECK(e.code() != Code::InternalError);
        CHECK(e.code() != Code::Ok);
        CHECK(std::string(e.what()).size() > 0);
      }
    }
  }
}
