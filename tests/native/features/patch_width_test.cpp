#include <doctest/doctest.h>

#include <cmath>

#include "features/edge_graph.h"
#include "features/patch_width.h"
#include "features/segmentation.h"
#include "features/test_shapes.h"

using namespace conformesh;
using namespace conformesh::features;

TEST_CASE("patchWidths: across a slab's rim strip its thickness, across a face its side") {
  const double t = 0.01;
  const EdgeGraph g = buildEdgeGraph(testshapes::box(4, 1.0, 1.0, t));
  const Segmentation seg = segment(g, FeatureOptions{});
  REQUIRE(seg.patches.size() == 6);
  const auto width = patchWidths(g, seg, 2.0);
  const auto narrow = patchWidths(g, seg, 0.5);
  int rimEdges = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    const auto& ev = g.edgeVerts[e];
    const Vec3 a = g.positions[ev[0]], b = g.positions[ev[1]];
    for (int s = 0; s < 2; ++s) {
      const uint32_t f = g.edgeFaces[e][s];
      const bool curve = seg.edgeKind[e] != EdgeKind::None;
      if (!curve) {
        CHECK(std::isinf(width[e][s]));  // inside a patch
        continue;
      }
      const Vec3 n = g.faceNormal(f);
      const bool rim = std::abs(n.z) < 0.5, horizontal = std::abs(a.z - b.z) < 1e-12;
      if (rim && horizontal) {
        // a long side of a rim strip: the other long side is t away
        CHECK(width[e][s] == doctest::Approx(t).epsilon(1e-9));
        CHECK(narrow[e][s] == doctest::Approx(t).epsilon(1e-9));
        ++rimEdges;
      } else if (!rim) {
        // the border of the top or bottom face: the opposite side is 1 away, beyond 0.5
        CHECK(width[e][s] == doctest::Approx(1.0).epsilon(1e-9));
        CHECK(std::isinf(narrow[e][s]));
      }
    }
  }
  CHECK(rimEdges == 2 * 4 * 4);  // two long sides of four strips, four edges each
}

TEST_CASE("patchWidths: the next edges along a curve and a right-angle corner are not across") {
  // a cube's faces are squares: every border edge sees only the opposite side, one away
  const EdgeGraph g = buildEdgeGraph(testshapes::cube(6));
  const Segmentation seg = segment(g, FeatureOptions{});
  REQUIRE(seg.patches.size() == 6);
  const auto width = patchWidths(g, seg, 0.9);
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    for (int s = 0; s < 2; ++s) CHECK(std::isinf(width[e][s]));
}
