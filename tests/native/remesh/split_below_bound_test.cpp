#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <set>

#include "remesh/planar_checks.h"
#include "remesh/split_below_bound.h"

using namespace conformesh;

namespace {

struct Planar {
  std::vector<double> xy;
  std::vector<uint32_t> tri;
  std::vector<uint8_t> fixed;
  std::vector<Vec3> pos;
};

// Boundary points (fixed) then interior points (free), in the plane z = 0.
Planar planar(const std::vector<std::array<double, 2>>& boundary, const std::vector<std::array<double, 2>>& interior,
              std::vector<uint32_t> tri) {
  Planar p;
  for (const auto* list : {&boundary, &interior})
    for (const auto& q : *list) {
      p.xy.insert(p.xy.end(), {q[0], q[1]});
      p.fixed.push_back(list == &boundary);
      p.pos.push_back({q[0], q[1], 0});
    }
  p.tri = std::move(tri);
  return p;
}

size_t below(const Planar& p, double bound) {
  size_t n = 0;
  for (size_t t = 0; t < p.tri.size() / 3; ++t)
    n += optimization::minAngleDeg3(p.pos[p.tri[3 * t]], p.pos[p.tri[3 * t + 1]], p.pos[p.tri[3 * t + 2]]) < bound;
  return n;
}

using testing::boundaryEdges;

const optimization::LiftFn kPlane = [](uint32_t, double x, double y, Vec3& out) {
  out = {x, y, 0};
  return true;
};

}  // namespace

TEST_CASE("a vertex serving three boundary segments gets a neighbour where moves and flips cannot reach the bound") {
  // b0..b3 a straight run of samples, one interior vertex v over all three segments: its two
  // outer triangles cannot both have 35° wherever v goes (at best about 30.5°), and no flip
  // helps (b0, b1, b2 are collinear)
  Planar p = planar({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 2.6}, {1.5, 2.6}, {0, 2.6}}, {{1.5, 0.9}},
                    {0, 1, 7, 1, 2, 7, 2, 3, 7, 3, 4, 7, 4, 5, 7, 5, 6, 7, 6, 0, 7});
  const double bound = 35;
  optimization::OptimizeOptions o;
  o.minAngleDeg = bound;
  o.boundPasses = 8;
  optimization::optimizePatch(p.xy, p.tri, p.pos, p.fixed, kPlane, o);
  const size_t before = below(p, bound);
  REQUIRE(before > 0);  // the premise: the optimization alone leaves triangles below the bound
  const auto edges = boundaryEdges(p.tri);
  const size_t nv = p.xy.size() / 2;
  const optimization::SplitStats st = optimization::splitBelowBound(p.xy, p.tri, p.pos, p.fixed, kPlane, o, {});
  CHECK(st.splits > 0);
  CHECK(below(p, bound) == 0);
  CHECK_FALSE(st.capped);
  CHECK(boundaryEdges(p.tri) == edges);  // the boundary and its samples untouched
  CHECK(p.xy.size() / 2 == nv + st.splits);
  CHECK(p.fixed.size() == nv + st.splits);
  for (size_t v = nv; v < p.fixed.size(); ++v) CHECK(p.fixed[v] == 0);
  for (size_t v = 0; v < nv; ++v)
    if (p.fixed[v]) CHECK(p.pos[v].x == p.xy[2 * v]);  // fixed vertices stay
  // a valid triangulation of the same region: every triangle counter-clockwise, the areas sum
  double area = 0;
  for (size_t t = 0; t < p.tri.size() / 3; ++t) {
    const double* a = &p.xy[2 * p.tri[3 * t]];
    const double* b = &p.xy[2 * p.tri[3 * t + 1]];
    const double* c = &p.xy[2 * p.tri[3 * t + 2]];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    CHECK(twice > 0);
    area += 0.5 * twice;
  }
  CHECK(area == doctest::Approx(3 * 2.6));
}

TEST_CASE("a triangle below the bound at an input corner of the patch is left as it is") {
  // the patch's whole angle at b0 is about 18°: no vertex can give its triangle more
  Planar p = planar({{0, 0}, {4, 0}, {4, 1.3}}, {{2.6, 0.45}}, {0, 1, 3, 1, 2, 3, 2, 0, 3});
  optimization::OptimizeOptions o;
  o.minAngleDeg = 30;
  const size_t before = below(p, 30);
  REQUIRE(before > 0);
  const std::vector<uint32_t> tri = p.tri;
  const optimization::SplitStats st = optimization::splitBelowBound(p.xy, p.tri, p.pos, p.fixed, kPlane, o, {});
  CHECK(st.attempts == 0);  // not even tried: each try costs a pass over the patch
  CHECK(p.tri == tri);
  CHECK(p.xy.size() == 8);
}
