// For every mesh in shared/data, meshInfo() and the halfedge topology queries after validate()
// match the MANIFEST's V, F, boundary loops, χ and genus.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mesh/mesh_io.h"
#include "mesh/topology.h"
#include "mesh/validate.h"
#include "mesh_io_test_util.h"

using namespace conformesh;

namespace {
struct ManifestRow {
  std::string file;
  long v = 0, f = 0, loops = 0, chi = 0, genus = 0;
};

std::string trimmed(const std::string& s) {
  size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Rows of the table "| file | origin | licence | V | F | bnd loops | chi | genus | ...".
std::vector<ManifestRow> readManifest(const std::string& path) {
  std::ifstream in(path);
  std::vector<ManifestRow> rows;
  std::string line;
  int iv = -1, iF = -1, iLoops = -1, iChi = -1, iGenus = -1;
  while (std::getline(in, line)) {
    if (line.size() < 2 || line[0] != '|') continue;
    std::vector<std::string> cols;
    std::stringstream ls(line.substr(1));
    std::string c;
    while (std::getline(ls, c, '|')) cols.push_back(trimmed(c));
    if (!cols.empty() && cols[0] == "file") {  // header: find the columns by name
      for (int i = 0; i < int(cols.size()); ++i) {
        if (cols[i] == "V") iv = i;
        if (cols[i] == "F") iF = i;
        if (cols[i] == "bnd loops") iLoops = i;
        if (cols[i] == "chi") iChi = i;
        if (cols[i] == "genus") iGenus = i;
      }
      continue;
    }
    if (iv < 0 || iF < 0 || iLoops < 0 || iChi < 0 || iGenus < 0) continue;
    if (cols.size() <= size_t(iGenus) || cols[0].find("---") != std::string::npos) continue;
    ManifestRow r;
    r.file = cols[0];
    r.v = std::stol(cols[iv]);
    r.f = std::stol(cols[iF]);
    r.loops = std::stol(cols[iLoops]);
    r.chi = std::stol(cols[iChi]);
    r.genus = std::stol(cols[iGenus]);
    rows.push_back(r);
  }
  return rows;
}
}  // namespace

TEST_CASE("shared data: meshInfo and validate() match the MANIFEST's V, F, loops, χ, genus") {
  const std::string dir = CONFORMESH_DATA_DIR;
  if (!std::ifstream(dir + "/MANIFEST.md")) {
    MESSAGE("no test data at " << dir << ": skipped");
    return;
  }
  std::vector<ManifestRow> rows = readManifest(dir + "/MANIFEST.md");
  REQUIRE(rows.size() >= 12);
  for (const ManifestRow& row : rows) {
    CAPTURE(row.file);
    ReadOptions ro;
    ro.fileName = row.file;
    ReadResult rr = readMesh(test::readFile(dir + "/" + row.file), ro);

    MeshInfo info = meshInfo(rr.mesh);
    CHECK(long(info.vertices) == row.v);
    CHECK(long(info.faces) == row.f);
    CHECK(long(info.boundaryLoops) == row.loops);
    CHECK(info.euler == row.chi);
    CHECK(info.genus == double(row.genus));
    // the MANIFEST's genus = (2·components − chi − loops) / 2 gives its components (ALSTOM_TEST4: 6)
    CHECK(2 * long(info.components) == row.chi + row.loops + 2 * row.genus);
    CHECK(info.nonManifoldEdges == 0);
    CHECK(info.degenerateFaces == 0);

    // The MANIFEST says every mesh is manifold and consistently oriented: validate() repairs
    // nothing (it may only drop unreferenced vertices) and the halfedge queries agree.
    ValidatedMesh vm = validate(rr.mesh);
    CHECK(vm.report.flippedFaces == 0);
    CHECK(vm.report.degenerateFaces == 0);
    CHECK(long(vm.mesh.vertexCount()) == row.v);
    CHECK(long(vm.mesh.faceCount()) == row.f);
    CHECK(eulerCharacteristic(vm.mesh) == row.chi);
    CHECK(genus(vm.mesh) == row.genus);
    CHECK(long(boundaryLoops(vm.mesh).size()) == row.loops);
  }
}
