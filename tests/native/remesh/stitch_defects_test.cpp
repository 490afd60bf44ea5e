#include <doctest/doctest.h>

#include <algorithm>

#include "remesh/stitch_defects.h"

using namespace conformesh;

namespace {
MeshBuffers triangles(std::vector<uint32_t> t, uint32_t vertices) {
  MeshBuffers m;
  for (uint32_t v = 0; v < vertices; ++v) m.positions.insert(m.positions.end(), {double(v), double(v * v % 7), 0.0});
  m.triangles = std::move(t);
  return m;
}
bool edgeIs(const MeshBuffers& m, size_t t, size_t c, uint32_t a, uint32_t b) {
  const uint32_t u = m.triangles[3 * t + c], w = m.triangles[3 * t + (c + 1) % 3];
  return (u == a && w == b) || (u == b && w == a);
}
}  // namespace

TEST_CASE("stitch defects: a chord that two patches both have inside is found once per patch") {
  // patch 0: (0,1,2), (0,2,3) share the chord 0-2; patch 1: (2,0,4), (0,2,5) share it too
  const MeshBuffers m = triangles({0, 1, 2, 0, 2, 3, 2, 0, 4, 0, 2, 5}, 6);
  const std::vector<uint32_t> patch = {0, 0, 1, 1};
  const auto chords = sharedChords(m, patch);
  REQUIRE(chords.size() == 2);
  CHECK(chords[0][0] == 0);
  CHECK(chords[1][0] == 2);
  for (const auto& [t, c] : chords) CHECK(edgeIs(m, t, c, 0, 2));
  CHECK(doubledTriangles(m, patch).empty());
}

TEST_CASE("stitch defects: a manifold stitch has none; a triangle both patches close is doubled") {
  // two patches meeting along the curve 0-2 (one triangle each side): manifold
  const MeshBuffers ok = triangles({0, 1, 2, 0, 2, 3}, 4);
  CHECK(sharedChords(ok, {0, 1}).empty());
  CHECK(doubledTriangles(ok, {0, 1}).empty());
  // the wedge 0-1-2 closed by both patches: (0,1,2) in patch 0 (two triangles), (2,1,0) in patch 1
  const MeshBuffers wedge = triangles({0, 1, 2, 1, 3, 2, 2, 1, 0}, 4);
  const auto doubled = doubledTriangles(wedge, {0, 0, 1});
  REQUIRE(doubled.size() == 1);
  CHECK(doubled[0] == 0);  // the larger patch re-meshes
}
