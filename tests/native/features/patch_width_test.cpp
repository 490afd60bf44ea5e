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

TEST_CASE("patchWidths: an inner curve is sampled as a border is, each side measured to what lies on it") {
  // a flat square with an inner crease along y = 0.1 from x = 0.3 to 0.7: below it the border
  // y = 0 is 0.1 away, above it the border y = 1 is 0.9 away (beyond the 0.5 searched)
  const int n = 20;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  const auto vertexAt = [&](double x, double y) {
    for (uint32_t v = 0; v < g.vertexCount; ++v)
      if (std::abs(g.positions[v].x - x) < 1e-12 && std::abs(g.positions[v].y - y) < 1e-12) return v;
    return kNone;
  };
  FeatureOptions o;
  o.innerCreases = true;
  for (int i = 6; i < 14; ++i) o.featureEdges.push_back({vertexAt(double(i) / n, 2.0 / n), vertexAt(double(i + 1) / n, 2.0 / n)});
  const Segmentation seg = segment(g, o);
  REQUIRE(seg.patches.size() == 1);
  const auto width = patchWidths(g, seg, 0.5);
  int inner = 0;
  for (const auto& fe : o.featureEdges) {
    const uint32_t e = g.findEdge(fe[0], fe[1]);
    REQUIRE(seg.isInnerCurve(seg.edgeCurve[e]));
    for (int s = 0; s < 2; ++s) {
      const auto& fv = g.faces[g.edgeFaces[e][s]];
      const bool below = g.positions[fv[0]].y + g.positions[fv[1]].y + g.positions[fv[2]].y < 0.3;  // centroid below 0.1
      if (below) CHECK(width[e][s] == doctest::Approx(0.1).epsilon(1e-9));
      else CHECK(std::isinf(width[e][s]));
    }
    ++inner;
  }
  CHECK(inner == 8);
}
