#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "planar/cdt.h"
#include "planar_test_util.h"

using namespace planar_test;

namespace {
Code codeOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return Code::Ok;
}
}  // namespace

TEST_CASE("CDT of the data PSLGs: every segment a chain, constrained Delaunay, holes removed") {
  for (const char* name : {"square_holes", "wiggly5000", "alligator_s3_lscm"}) {
    CAPTURE(name);
    Pslg in = loadPoly(name);
    PlanarMesh m = triangulatePslg(in);
    MeshCheck c = checkMesh(m, in, true);
    CHECK(m.triangleCount() > 0);
    CHECK(c.inverted == 0);
    CHECK(c.nonManifold == 0);
    CHECK(c.notDelaunay == 0);
    CHECK(c.segmentsBroken == 0);
    CHECK(c.inputMissing == 0);
    CHECK(c.paramOff == 0);
    // No Steiner points in a CDT: V - E + F with the boundary gives the same vertex set.
    CHECK(m.vertexCount() == in.points.size() / 2);
    for (size_t k = 0; k < in.holes.size() / 2; ++k) {
      const double* h = &in.holes[2 * k];
      for (size_t t = 0; t < m.triangleCount(); ++t) {
        const uint32_t* v = &m.triangles[3 * t];
        bool inside = orient2d(P(m, v[0]), P(m, v[1]), h) > 0 && orient2d(P(m, v[1]), P(m, v[2]), h) > 0 &&
                      orient2d(P(m, v[2]), P(m, v[0]), h) > 0;
        CHECK_FALSE(inside);
      }
    }
  }
}

TEST_CASE("Delaunay triangulation of a cocircular grid with the convex hull") {
  Pslg in;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) in.points.insert(in.points.end(), {0.1 * i, 0.1 * j});
  CdtOptions o;
  o.convexHull = true;
  PlanarMesh m = triangulatePslg(in, o);
  MeshCheck c = checkMesh(m, in, true);
  CHECK(m.triangleCount() == 2 * 29 * 29);  // Euler: every grid vertex used, convex hull a square
  CHECK(c.inverted == 0);
  CHECK(c.notDelaunay == 0);
  CHECK(c.nonManifold == 0);
  CHECK(std::fabs(meshArea(m) - 2.9 * 2.9) < 1e-9);
}

TEST_CASE("random points and a random non-crossing segment set") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  Pslg in;
  for (int i = 0; i < 2000; ++i) in.points.insert(in.points.end(), {U(rng), U(rng)});
  // Segments: a few disjoint horizontal chords between existing points sorted by x per band.
  for (int band = 0; band < 10; ++band) {
    std::vector<uint32_t> ids;
    for (uint32_t i = 0; i < 2000; ++i)
      if (in.points[2 * i + 1] >= band * 0.1 + 0.04 && in.points[2 * i + 1] < band * 0.1 + 0.06) ids.push_back(i);
    std::sort(ids.begin(), ids.end(), [&](uint32_t a, uint32_t b) { return in.points[2 * a] < in.points[2 * b]; });
    for (size_t k = 0; k + 1 < ids.size(); ++k) in.segments.insert(in.segments.end(), {ids[k], ids[k + 1]});
  }
  CdtOptions o;
  o.convexHull = true;
  PlanarMesh m = triangulatePslg(in, o);
  MeshCheck c = checkMesh(m, in, true);
  CHECK(c.inverted == 0);
  CHECK(c.notDelaunay == 0);
  CHECK(c.segmentsBroken == 0);
  CHECK(c.nonManifold == 0);
}

TEST_CASE("holes by orientation and by seed give the same domain") {
  Pslg in;
  in.points = {0, 0, 4, 0, 4, 4, 0, 4, 1, 1, 1, 3, 3, 3, 3, 1};  // outer CCW, inner CW
  in.segments = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  CdtOptions o;
  o.holesByOrientation = true;
  PlanarMesh a = triangulatePslg(in, o);
  CHECK(std::fabs(meshArea(a) - 12.0) < 1e-12);
  Pslg seeded = in;
  seeded.holes = {2, 2};
  PlanarMesh b = triangulatePslg(seeded);
  CHECK(std::fabs(meshArea(b) - 12.0) < 1e-12);
  PlanarMesh full = triangulatePslg(in);  // no seed, default: the inner square stays
  CHECK(std::fabs(meshArea(full) - 16.0) < 1e-12);
}

TEST_CASE("a vertex on a segment splits it; duplicates are merged") {
  Pslg in;
  in.points = {0, 0, 2, 0, 2, 2, 0, 2, 1, 0, 2, 2};  // vertex 4 on segment 0-1, vertex 5 = vertex 2
  in.segments = {0, 1, 1, 2, 2, 3, 3, 0};
  PlanarMesh m = triangulatePslg(in);
  Pslg viaDuplicate = in;
  viaDuplicate.segments[3] = 5;
  CHECK(std::fabs(meshArea(triangulatePslg(viaDuplicate)) - 4.0) < 1e-12);
  MeshCheck c = checkMesh(m, in, true);
  CHECK(c.segmentsBroken == 0);
  CHECK(std::fabs(meshArea(m) - 4.0) < 1e-12);
  CHECK(m.vertexCount() == 6);
  for (uint32_t v : m.triangles) CHECK(v != 5);
  CHECK(m.vertexSegment[4] == 0);
  CHECK(m.vertexParam[4] == doctest::Approx(0.5));
}

TEST_CASE("invalid PSLGs are reported with a code") {
  Pslg cross;
  cross.points = {0, 0, 1, 1, 0, 1, 1, 0};
  cross.segments = {0, 1, 2, 3};
  CHECK(codeOf([&] { triangulatePslg(cross); }) == Code::InvalidPslg);
  Pslg overlap;
  overlap.points = {0, 0, 1, 0, 2, 0, 3, 0, 0, 1};
  overlap.segments = {0, 2, 1, 3};
  CHECK(codeOf([&] { triangulatePslg(overlap); }) == Code::InvalidPslg);
  Pslg collinear;
  collinear.points = {0, 0, 1, 1, 2, 2};
  CHECK(codeOf([&] { triangulatePslg(collinear); }) == Code::InvalidPslg);
  Pslg range;
  range.points = {0, 0, 1, 0, 0, 1};
  range.segments = {0, 3};
  CHECK(codeOf([&] { triangulatePslg(range); }) == Code::IndexOutOfRange);
  Pslg nan = range;
  nan.segments = {0, 1};
  nan.points[3] = std::nan("");
  CHECK(codeOf([&] { triangulatePslg(nan); }) == Code::NonFiniteCoordinate);
  Pslg open;  // an open polyline encloses nothing
  open.points = {0, 0, 1, 0, 1, 1, 0, 1};
  open.segments = {0, 1, 1, 2, 2, 3};
  CHECK(codeOf([&] { triangulatePslg(open); }) == Code::InvalidPslg);
  CdtOptions hull;
  hull.convexHull = true;
  CHECK(std::fabs(meshArea(triangulatePslg(open, hull)) - 1.0) < 1e-12);
  Pslg pointsOnly;
  pointsOnly.points = {0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0.5};
  CHECK(std::fabs(meshArea(triangulatePslg(pointsOnly)) - 1.0) < 1e-12);
  Pslg degenerate;
  degenerate.points = {0, 0, 1, 0, 0, 1, 0, 0};
  degenerate.segments = {0, 3};
  CHECK(codeOf([&] { triangulatePslg(degenerate); }) == Code::InvalidPslg);
}
