#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>

#include "features/test_shapes.h"
#include "remesh/limits.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {
double secondsOf(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

TEST_CASE("remesh limits: an output far above maxTriangles is TooLarge before the heavy work") {
  // target 1e-4 · diagonal on a cube: about 6 / (√3/4 · (1.7e-4)²) ≈ 5e8 triangles, far beyond any
  // memory; the estimate must stop it before flattening and refinement.
  RemeshOptions o;
  o.targetEdgeLengthRel = 1e-4;
  o.minEdgeLength = 1e-4;  // keep the curvature clamp out of the way
  auto t0 = std::chrono::steady_clock::now();
  RemeshResult r = remesh(testshapes::cube(3), o);
  CHECK(secondsOf(t0) < 2.0);
  REQUIRE(r.status.code == Code::TooLarge);
  CHECK(r.status.message.find("triangles") != std::string::npos);
  CHECK(r.status.message.find(std::to_string(o.maxTriangles)) != std::string::npos);
  CHECK(r.mesh.triangleCount() == 0);

  // a tiny limit on a small job
  o = {};
  o.targetEdgeLengthRel = 0.05;
  o.maxTriangles = 10;
  r = remesh(testshapes::cube(4), o);
  REQUIRE(r.status.code == Code::TooLarge);
  CHECK(r.status.message.find("maxTriangles = 10 ") != std::string::npos);
  o.maxTriangles = size_t(32) << 20;
  o.maxVertices = 10;
  CHECK(remesh(testshapes::cube(4), o).status.code == Code::TooLarge);
  o.maxVertices = size_t(16) << 20;
  o.maxMemoryBytes = 1e5;
  r = remesh(testshapes::cube(4), o);
  CHECK(r.status.code == Code::TooLarge);
  CHECK(r.status.message.find("bytes") != std::string::npos);
}

TEST_CASE("remesh limits: a generous limit passes, and the estimate is close to the real count") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.computeHausdorff = false;
  o.maxTriangles = 100000;
  o.maxVertices = 50000;
  o.maxMemoryBytes = 1e9;
  RemeshResult r = remesh(testshapes::cube(4), o);
  REQUIRE_MESSAGE(r.status.ok(), r.status.message);
  const double real = double(r.report.triangles), est = r.report.estimatedTriangles;
  INFO("estimated " << est << ", real " << real);
  CHECK(est > 0.5 * real);
  CHECK(est < 2.0 * real);
  // a limit just above the real count passes when the estimate is below it too
  o.maxTriangles = size_t(std::max(real, est)) + 1;
  CHECK(remesh(testshapes::cube(4), o).status.ok());
}

TEST_CASE("remesh limits: the estimate counts the grading at a thin strip") {
  // a 1 × 1 × t slab: its rim is four strips of width t between creases, far narrower than the
  // target edge length; the refinement samples them at about t and grades away from them
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.computeHausdorff = false;
  for (double t : {0.02, 0.005}) {
    RemeshResult r = remesh(testshapes::box(4, 1.0, 1.0, t), o);
    REQUIRE_MESSAGE(r.status.ok(), r.status.message);
    const double real = double(r.report.triangles), est = r.report.estimatedTriangles;
    INFO("thickness " << t << ": estimated " << est << ", real " << real);
    CHECK(real >= 0.75 * est);
    CHECK(real <= 1.33 * est);
  }
}

TEST_CASE("remesh limits: 0 is not 'unlimited' but InvalidArgument; real counts are checked") {
  RemeshOptions o;
  o.maxTriangles = 0;
  CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);
  o = {};
  o.maxVertices = 0;
  CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);
  o = {};
  o.maxMemoryBytes = 0;
  CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);

  o = {};
  o.maxTriangles = 100;
  o.maxVertices = 60;
  CHECK_NOTHROW(checkOutputCounts(60, 100, o));
  try {
    checkOutputCounts(60, 101, o);
    FAIL("no TooLarge");
  } catch (const Error& e) {
    CHECK(e.code() == Code::TooLarge);
    CHECK(std::string(e.what()).find("101 triangles, above maxTriangles = 100") != std::string::npos);
  }
  try {
    checkOutputCounts(61, 100, o);
    FAIL("no TooLarge");
  } catch (const Error& e) {
    CHECK(e.code() == Code::TooLarge);
  }
}
