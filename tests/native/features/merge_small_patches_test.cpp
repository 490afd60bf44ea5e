#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "features/edge_graph.h"
#include "features/merge_small_patches.h"
#include "features/patch_mesh.h"
#include "features/segmentation.h"
#include "features/sizing.h"
#include "mesh/mesh_io.h"

using namespace conformesh;
using namespace conformesh::features;

namespace {
// Patches of area below minArea with a cut to a neighbour.
size_t smallBesideCuts(const EdgeGraph& g, const Segmentation& s, double minArea) {
  std::vector<double> area(s.patches.size(), 0.0);
  for (size_t p = 0; p < s.patches.size(); ++p)
    for (uint32_t f : s.patches[p]) area[p] += g.faceArea(f);
  std::vector<uint8_t> small(s.patches.size(), 0);
  for (const Curve& c : s.curves)
    if (c.kind == EdgeKind::Cut && c.patches[0] != kNone && c.patches[1] != kNone && c.patches[0] != c.patches[1])
      for (uint32_t p : c.patches) small[p] = small[p] || area[p] < minArea;
  size_t n = 0;
  for (uint8_t x : small) n += x;
  return n;
}
}  // namespace

TEST_CASE("features: mergeSmallPatches merges patches of a few output triangles across cuts; features stay, patches stay disks (man, armadillo)") {
  for (const char* name : {"man.off", "armadillo.off"}) {
    CAPTURE(name);
    std::ifstream in(std::string(CONFORMESH_DATA_DIR) + "/" + name, std::ios::binary);
    REQUIRE(in);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const EdgeGraph g = buildEdgeGraph(readMesh(bytes).mesh);
    const double target = 0.01 * boundingBoxDiagonal(g);
    FeatureOptions fo;
    fo.minFeatureLength = 2 * target;  // creases as the remesh finds them at 1 %
    const Segmentation before = segment(g, fo);  // junctionScale 0: no merge, no junction repairs
    const double minArea = 4 * target * target;
    REQUIRE(smallBesideCuts(g, before, minArea) > 0);  // the cutting leaves such patches
    Segmentation after = before;
    const uint32_t merges = mergeSmallPatches(g, after, minArea);
    CHECK(merges > 0);
    CHECK(after.patches.size() + merges == before.patches.size());
    CHECK(smallBesideCuts(g, after, minArea) < smallBesideCuts(g, before, minArea));
    const std::vector<uint8_t> mask = after.curveMask();
    for (const auto& faces : after.patches) CHECK(extractPatch(g, mask, faces).isDisk());
    uint32_t changed = 0;  // only cuts go: features and boundaries stay, no cut is added
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      changed += after.edgeKind[e] != before.edgeKind[e] && !(before.edgeKind[e] == EdgeKind::Cut && after.edgeKind[e] == EdgeKind::None);
    CHECK(changed == 0);
  }
}
