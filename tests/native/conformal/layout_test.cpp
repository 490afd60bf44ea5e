#include <doctest/doctest.h>

#include <utility>
#include <vector>

#include "conformal/layout.h"

using namespace conformesh;

TEST_CASE("layout: boundary crossings: collinear disjoint segments do not cross, touching ones do") {
  // a straight polyline 0-1-2-3 on the x axis: non-adjacent pieces are collinear and disjoint
  std::vector<double> xy = {0, 0, 1, 0, 2, 0, 3, 0};
  std::vector<std::pair<int, int>> seg = {{0, 1}, {1, 2}, {2, 3}};
  CHECK(conformal::countSegmentCrossings(xy, seg) == 0);
  // the same, 1000 long and 1 wide: the outline of a long strip is simple
  xy.clear();
  seg.clear();
  const int n = 1000;
  for (int i = 0; i <= n; ++i) xy.insert(xy.end(), {double(i), 0.0});
  for (int i = n; i >= 0; --i) xy.insert(xy.end(), {double(i), 1.0});
  const int m = int(xy.size() / 2);
  for (int i = 0; i < m; ++i) seg.push_back({i, (i + 1) % m});
  CHECK(conformal::countSegmentCrossings(xy, seg) == 0);
  // collinear overlap, an endpoint touching the inside of another segment, a proper crossing
  xy = {0, 0, 2, 0, 1, 0, 3, 0};
  CHECK(conformal::countSegmentCrossings(xy, {{0, 1}, {2, 3}}) == 1);
  xy = {0, 0, 2, 0, 1, 0, 1, 1};
  CHECK(conformal::countSegmentCrossings(xy, {{0, 1}, {2, 3}}) == 1);
  xy = {0, 0, 2, 2, 0, 2, 2, 0};
  CHECK(conformal::countSegmentCrossings(xy, {{0, 1}, {2, 3}}) == 1);
  // c on the line through a b but beyond b, d off the line: no intersection
  xy = {0, 0, 1, 0, 2, 0, 2, 1};
  CHECK(conformal::countSegmentCrossings(xy, {{0, 1}, {2, 3}}) == 0);
}
