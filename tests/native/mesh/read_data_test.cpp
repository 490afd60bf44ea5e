// Every test mesh in shared/data reads with the vertex and triangle counts of its MANIFEST row
// (V = vertices used by some face, F = triangles after fan triangulation).
#include <doctest/doctest.h>

#include <set>
#include <sstream>

#include "mesh/mesh_io.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::test;

namespace {

struct Row {
  std::string file;
  size_t v = 0, f = 0;
};

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<Row> manifestRows() {
  std::vector<uint8_t> bytes = readFile(std::string(CONFORMESH_DATA_DIR) + "/MANIFEST.md");
  std::istringstream in(std::string(bytes.begin(), bytes.end()));
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 2 || line[0] != '|') continue;
    std::vector<std::string> cols;
    std::stringstream ls(line.substr(1));
    std::string c;
    while (std::getline(ls, c, '|')) cols.push_back(trim(c));
    if (cols.size() < 5 || cols[0] == "file" || cols[0].find("---") != std::string::npos) continue;
    Row r;
    r.file = cols[0];
    r.v = std::stoul(cols[3]);
    r.f = std::stoul(cols[4]);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("shared data: every MANIFEST mesh reads with its V and F") {
  std::vector<Row> rows = manifestRows();
  REQUIRE(rows.size() >= 12);
  for (const Row& row : rows) {
    CAPTURE(row.file);
    std::vector<uint8_t> bytes = readFile(std::string(CONFORMESH_DATA_DIR) + "/" + row.file);
    REQUIRE(!bytes.empty());
    // Detected from the content alone, and the same with the file name as a hint.
    ReadResult r = readMesh(bytes);
    ReadOptions named;
    named.fileName = row.file;
    ReadResult r2 = readMesh(bytes, named);
    CHECK(r.format == r2.format);
    CHECK(r.mesh.triangles == r2.mesh.triangles);
    std::set<uint32_t> used(r.mesh.triangles.begin(), r.mesh.triangles.end());
    CHECK(used.size() == row.v);
    CHECK(r.mesh.triangleCount() == row.f);
  }
}
