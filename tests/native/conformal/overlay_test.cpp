#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "conformesh.h"
#include "test_meshes.h"

using namespace conformesh;

namespace {

// Hinted and plain point location agree bit for bit on random points of the layout's bounding
// box (inside, near and outside the domain), with hints near the point (the face of the
// previous point of a short random walk) and far from it (a random face). Returns the share of
// inside points the walk decided (the rest fell back to the grid search).
double checkHintedLocate(const FlatPatch& P, int samples, unsigned seed) {
  REQUIRE(P.report.invertedTriangles == 0);
  REQUIRE(P.report.boundaryCrossings == 0);
  const MeshBuffers& L = P.layout;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (size_t v = 0; v < L.vertexCount(); ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], L.positions[3 * v + k]);
      hi[k] = std::max(hi[k], L.positions[3 * v + k]);
    }
  const double w = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::uniform_int_distribution<int> F(0, int(L.triangleCount()) - 1);
  double x = 0.5 * (lo[0] + hi[0]), y = 0.5 * (lo[1] + hi[1]);
  int nearHint = -1, inside = 0, walked = 0;
  for (int s = 0; s < samples; ++s) {
    if (s % 4 == 0) {  // a jump anywhere in the (slightly enlarged) bounding box
      x = lo[0] - 0.05 * w + 1.1 * w * U(rng);
      y = lo[1] - 0.05 * w + 1.1 * w * U(rng);
    } else {  // a short step from the previous point
      x += 0.02 * w * (U(rng) - 0.5);
      y += 0.02 * w * (U(rng) - 0.5);
    }
    PullbackPoint plain;
    const bool okPlain = P.pullback.locate(x, y, plain);
    for (int hint : {nearHint, F(rng)}) {
      PullbackPoint hinted;
      const bool okHinted = P.pullback.locate(x, y, hint, hinted);
      INFO("sample " << s << " at (" << x << ", " << y << "), hint " << hint);
      REQUIRE(okHinted == okPlain);
      if (!okPlain) continue;
      CHECK(hinted.face == plain.face);
      CHECK(hinted.layoutFace == plain.layoutFace);
      CHECK(std::memcmp(hinted.bary, plain.bary, sizeof plain.bary) == 0);
      CHECK(std::memcmp(hinted.position, plain.position, sizeof plain.position) == 0);
      CHECK(hinted.margin == plain.margin);
      if (hint >= 0) {
        ++inside;
        walked += hinted.walkSteps >= 0;
      }
    }
    if (okPlain) nearHint = plain.layoutFace;
  }
  return inside > 0 ? double(walked) / inside : 0.0;
}

}  // namespace

TEST_CASE("overlay: hinted locate returns exactly what the grid search returns (spherical cap, free boundary)") {
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  const FlatPatch P = flatten(testmesh::sphericalCap(10, 40, 1.3), o);
  CHECK(checkHintedLocate(P, 4000, 21) > 0.99);
}

TEST_CASE("overlay: hinted locate on a domain with holes (walks stop at hole boundaries)") {
  const MeshBuffers M = testmesh::readTestMesh(std::string(CONFORMESH_DATA_DIR) + "/holes.off");
  REQUIRE(M.triangleCount() > 0);
  const FlatPatch P = flatten(M);
  REQUIRE(P.boundaryLoops.size() > 1);
  // a walk from a far random hint often runs into a hole and falls back to the grid search
  // (measured: ~70% of the walks end in the face)
  CHECK(checkHintedLocate(P, 4000, 22) > 0.5);
}
