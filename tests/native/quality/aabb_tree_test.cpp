#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "quality/aabb_tree.h"
#include "quality/metrics.h"
#include "quality_test_meshes.h"

using namespace conformesh;
using namespace conformesh::quality;

namespace {

//! A wavy grid on [0,1]² with a flat third (many equal distances) and a column of needles.
MeshBuffers wavyGrid(int n) {
  MeshBuffers m = quality_test::grid(n, [](double x, double y) { return x < 0.3 ? 0.0 : 0.2 * std::sin(7 * x) * std::cos(5 * y); });
  for (int j = 0; j <= n; ++j) m.positions[3 * size_t(j * (n + 1) + n / 2)] += 0.49 / n;  // squeeze a column
  return m;
}

struct Lcg {
  uint64_t s;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) * (1.0 / 9007199254740992.0);
  }
};

double bruteForce(const TriangleMeshDistance& d, const MeshBuffers& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (uint32_t f = 0; f < m.triangleCount(); ++f) best = std::min(best, d.faceDistanceSquared(f, p));
  return best;
}

}  // namespace

TEST_CASE("AABB tree: closest triangle equals brute force, on median and Morton trees") {
  MeshBuffers m = wavyGrid(24);
  Lcg rng{7};
  for (AabbSplit split : {AabbSplit::Median, AabbSplit::Morton}) {
    TriangleMeshDistance d(m, split);
    int64_t hint = -1;
    for (int i = 0; i < 400; ++i) {
      // points near the surface (most queries of a Hausdorff distance) and far from it
      Vec3 p{1.4 * rng.next() - 0.2, 1.4 * rng.next() - 0.2, (i % 4 == 0 ? 2.0 : 0.1) * (rng.next() - 0.5)};
      const double exact = bruteForce(d, m, p);
      const ClosestHit plain = d.closest(p);
      const ClosestHit hinted = d.closest(p, hint);
      CHECK(plain.distanceSquared == exact);
      CHECK(hinted.distanceSquared == exact);
      REQUIRE(plain.primitive >= 0);
      CHECK(d.faceDistanceSquared(uint32_t(plain.primitive), p) == exact);
      // early stop: a witness within the radius when one exists, else the closest
      for (double stop : {0.25 * exact, exact, 4 * exact + 1e-6}) {
        const ClosestHit w = d.closest(p, hint, stop);
        REQUIRE(w.primitive >= 0);
        CHECK(d.faceDistanceSquared(uint32_t(w.primitive), p) == w.distanceSquared);
        if (exact <= stop)
          CHECK(w.distanceSquared <= stop);
        else
          CHECK(w.distanceSquared == exact);
      }
      hint = plain.primitive;
    }
  }
}

TEST_CASE("AABB tree: withinNear finds only witnesses, and a triangle's own neighbourhood holds it") {
  MeshBuffers m = wavyGrid(16);
  std::vector<Box3> boxes(m.triangleCount());
  for (size_t f = 0; f < m.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.triangles[3 * f + k];
      boxes[f].add(Vec3{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]});
    }
  TriangleMeshDistance d(m);
  auto distSq = [&](uint32_t f, const Vec3& q) { return d.faceDistanceSquared(f, q); };
  for (AabbSplit split : {AabbSplit::Median, AabbSplit::Morton}) {
    AabbTree tree(boxes, split);
    CHECK(tree.size() == m.triangleCount());
    for (uint32_t f = 0; f < m.triangleCount(); f += 7) {
      const uint32_t* t = &m.triangles[3 * size_t(f)];
      Vec3 c{0, 0, 0};
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) c[j] += m.positions[3 * size_t(t[k]) + j] / 3;
      // the centroid lies on f: found at level 0 (f's own leaf)
      ClosestHit own = tree.withinNear(c, distSq, 1e-20, f, 0);
      REQUIRE(own.primitive >= 0);
      CHECK(own.distanceSquared <= 1e-20);
      // far above the surface nothing is within a small radius
      Vec3 far{c[0], c[1], c[2] + 5};
      CHECK(tree.withinNear(far, distSq, 1.0, f, 3).primitive == -1);
      CHECK(tree.withinNear(far, distSq, 1.0, f, 64).primitive == -1);  // the whole tree
    }
  }
}
