// Error-driven remeshing (RemeshOptions::maxError, remesh/max_error.h): the output's Hausdorff
// distance to the input, measured here with more samples than the report's, is within the bound;
// the angle bound holds; a looser bound gives a coarser mesh; bad values are InvalidArgument.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "features/test_shapes.h"
#include "quality/metrics.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {

RemeshResult withinError(const MeshBuffers& in, double rel) {
  RemeshOptions o;
  o.maxErrorRel = rel;
  o.hausdorffSamples = 20000;
  RemeshResult r = remesh(in, o);
  REQUIRE_MESSAGE(r.status.ok(), r.status.message);
  quality::HausdorffOptions ho;
  ho.samplesPerSide = 200000;
  ho.seed = 7;  // other points than the report's
  const quality::HausdorffResult h = quality::hausdorffDistance(r.mesh, in, ho);
  INFO("bound " << rel << ", measured " << h.relative << ", report " << r.report.hausdorffRel);
  CHECK(h.relative <= rel);
  CHECK(r.report.hausdorffRel <= rel);
  CHECK(r.report.trianglesBelowBoundOutsideExempt == 0);
  CHECK(r.report.topologyPreserved);
  return r;
}

}  // namespace

TEST_CASE("max error: a torus within two bounds, the looser one coarser") {
  const MeshBuffers torus = testshapes::torus(96, 36);
  const RemeshResult fine = withinError(torus, 1e-3), coarse = withinError(torus, 4e-3);
  CHECK(coarse.mesh.triangleCount() < fine.mesh.triangleCount());
}

TEST_CASE("max error: a spike tip off the curves is reached below a tenth of the target") {
  // a horn of angle sum about 220° at its tip, no crease reaching it (testshapes::spike): edges
  // of a tenth of the target around the tip cut about 8e-4 of the diagonal off it, above the
  // bound of 5e-4, whatever the chord tolerance
  const RemeshResult r = withinError(testshapes::spike(0.13, 0.1), 5e-4);
  CHECK(r.report.hausdorffRel > 0);
}

TEST_CASE("max error: a cube (flat faces) keeps its edges and grows its triangles") {
  // flat faces: no chord error anywhere, so the sizes are the largest allowed, far above the
  // default target edge length
  const MeshBuffers cube = testshapes::cube(8);
  const RemeshResult r = withinError(cube, 1e-3);
  RemeshOptions defaults;
  defaults.hausdorffSamples = 2000;
  const RemeshResult d = remesh(cube, defaults);
  REQUIRE(d.status.ok());
  CHECK(r.mesh.triangleCount() < d.mesh.triangleCount());
  CHECK(r.report.featureCurvesKept == r.report.featureCurves);
}

TEST_CASE("max error: the facets of a rough sheet are no creases there either, and the bound holds") {
  // The crease tests decide as without a bound; a sharp edge they drop is held to the bound by
  // the sizing (a bend the output spans), not made a curve of its own.
  const MeshBuffers sheet = testshapes::roughSheet(16, 0.12);
  const RemeshResult r = withinError(sheet, 4e-3);
  RemeshOptions defaults;
  defaults.hausdorffSamples = 2000;
  const RemeshResult d = remesh(sheet, defaults);
  REQUIRE(d.status.ok());
  INFO("sharp edges kept " << r.report.sharpEdges << ", dropped " << r.report.droppedFeatureEdges);
  CHECK(r.report.sharpEdges == d.report.sharpEdges);
  CHECK(r.report.droppedFeatureEdges > r.report.sharpEdges);
}

TEST_CASE("max error: non-finite bounds and a negative maxErrorRel are InvalidArgument; maxError < 0 defers to maxErrorRel, 0 is off") {
  for (double bad : {double(NAN), double(INFINITY), -double(INFINITY)}) {
    RemeshOptions o;
    o.maxError = bad;
    CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);
  }
  for (double bad : {-1e-3, double(NAN), double(INFINITY)}) {
    RemeshOptions o;
    o.maxErrorRel = bad;
    CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);
  }
  RemeshOptions off;
  off.hausdorffSamples = 2000;
  const RemeshResult plain = remesh(testshapes::cube(4), off);
  REQUIRE(plain.status.ok());
  RemeshOptions negative = off, zero = off;
  negative.maxError = -5;  // maxErrorRel is 0: off
  zero.maxError = 0;       // off, whatever maxErrorRel says
  zero.maxErrorRel = 1e-3;
  for (const RemeshOptions& o : {negative, zero}) {
    const RemeshResult r = remesh(testshapes::cube(4), o);
    REQUIRE(r.status.ok());
    CHECK(r.mesh.positions == plain.mesh.positions);
    CHECK(r.mesh.triangles == plain.mesh.triangles);
  }
}

// Above the bound, the next attempt cuts the sizes where the distance was exceeded, at the same
// tolerance: a cut-off tip is a local excess, which a tighter tolerance mends only by refining
// everywhere. A cone over a disk: its tip's error is the cone's slope times the distance to the
// nearest output vertex.
TEST_CASE("max error: a cone's tip cut off by the first attempt is mended by sizes cut there, not a tighter tolerance") {
  const MeshBuffers cone = testshapes::raisedDisk([](double r) { return 1.0 * (1 - r); });
  const RemeshResult r = withinError(cone, 1e-3);
  std::vector<std::string> attempts;
  for (const std::string& w : r.report.warnings)
    if (w.rfind("max error: attempt", 0) == 0) attempts.push_back(w);
  std::string all;
  for (const std::string& a : attempts) all += "\n  " + a;
  INFO(attempts.size() << " attempts:" << all);
  REQUIRE(attempts.size() >= 2);
  CHECK(attempts[0].find("sizes cut") == std::string::npos);
  CHECK(attempts[1].find("sizes cut") != std::string::npos);
  // the same tolerance, and less than twice the triangles: the sizes were cut near the tip only
  // (cut everywhere, by the 0.27 this excess asks for, they would be about 13 times as many)
  const auto tolerance = [](const std::string& w) {
    const size_t at = w.find("tolerance ");
    return w.substr(at, w.find_first_of("),", at) - at);
  };
  const auto triangles = [](const std::string& w) { return std::stod(w.substr(w.rfind(", ") + 2)); };
  CHECK(tolerance(attempts[1]) == tolerance(attempts[0]));
  CHECK(triangles(attempts[1]) <= 2 * triangles(attempts[0]));
  // with them on from the start, one attempt
  RemeshOptions o;
  o.maxErrorRel = 1e-3;
  o.coneTips = true;
  const RemeshResult tips = remesh(cone, o);
  REQUIRE(tips.status.ok());
  CHECK(tips.report.hausdorffRel <= 1e-3);
}
