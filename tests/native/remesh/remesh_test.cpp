#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "features/test_shapes.h"
#include "mesh/mesh_io.h"
#include "../mesh/mesh_io_test_util.h"
#include "quality/metrics.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {
// Properties every remesh output must have: manifold, same topology as the input, vertices on the
// input surface, min 3D angle >= bound except around the listed exempt corners.
// `flat`: the shape is flat between its features, so the mean edge length is the target (on a
// curved shape the chord tolerance makes it smaller).
// `bound`: assert the angle bound outside exempt corners (false: reported only).
RemeshResult checkRemesh(const MeshBuffers& in, const RemeshOptions& o, const char* name, bool flat = true, bool bound = true) {
  INFO(name);
  RemeshResult r = remesh(in, o);
  REQUIRE_MESSAGE(r.status.ok(), r.status.message);
  const MeshBuffers& m = r.mesh;
  REQUIRE(m.triangleCount() > 0);
  auto ti = quality::topologySummary(in), to = quality::topologySummary(m);
  CHECK(to.nonManifoldEdges == 0);
  CHECK(to.components == ti.components);
  CHECK(to.boundaryLoops == ti.boundaryLoops);
  CHECK(to.genus == ti.genus);
  CHECK(r.report.topologyPreserved);
  // consistent orientation: every interior edge used once in each direction
  std::set<std::pair<uint32_t, uint32_t>> directed;
  for (size_t t = 0; t < m.triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) CHECK(directed.insert({m.triangles[t + c], m.triangles[t + (c + 1) % 3]}).second);
  // on the input surface
  quality::TriangleMeshDistance dist(in);
  double diag = r.report.targetEdgeLength / o.targetEdgeLengthRel;
  double worst = 0;
  for (size_t v = 0; v < m.vertexCount(); ++v)
    worst = std::max(worst, dist.closest({m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}).distanceSquared);
  CHECK(std::sqrt(worst) <= 1e-9 * diag);
  // every feature curve is made of output edges
  CHECK(r.report.featureCurvesKept == r.report.featureCurves);
  // angle bound outside exempt corners
  if (bound) {
    CHECK(r.report.trianglesBelowBoundOutsideExempt == 0);
    CHECK(r.report.minAngleOutsideExempt >= o.minAngle - 1e-9);
  } else {
    MESSAGE(std::string(name) << ": " << r.report.trianglesBelowBoundOutsideExempt << " of " << r.report.triangles
                 << " triangles below the bound outside exempt corners (not yet asserted)");
  }
  // size: mean edge length near the target (flat shapes)
  if (flat) CHECK(r.report.meanEdgeLength > 0.6 * r.report.targetEdgeLength);
  CHECK(r.report.meanEdgeLength < 1.4 * r.report.targetEdgeLength);
  return r;
}
}  // namespace

TEST_CASE("remesh: cube keeps its 12 edges, 30 degree bound, vertices on the surface") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.hausdorffSamples = 2000;
  checkRemesh(testshapes::cube(4), o, "cube");
}

TEST_CASE("remesh: cylinder with caps") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.hausdorffSamples = 2000;
  checkRemesh(testshapes::cylinder(48, 12, 6), o, "cylinder", false);
}

TEST_CASE("remesh: torus (genus 1)") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.04;
  o.hausdorffSamples = 2000;
  checkRemesh(testshapes::torus(64, 24), o, "torus", false);
}

TEST_CASE("remesh: bad options and bad input come back as a status") {
  RemeshOptions o;
  o.minAngle = 50;
  RemeshResult r = remesh(testshapes::cube(2), o);
  CHECK(r.status.code == Code::InvalidArgument);
  o = {};
  o.targetEdgeLength = 0;  // a length is > 0, or < 0 for targetEdgeLengthRel times the diagonal
  CHECK(remesh(testshapes::cube(2), o).status.code == Code::InvalidArgument);
  MeshBuffers empty;
  r = remesh(empty, RemeshOptions{});
  CHECK_FALSE(r.status.ok());
  o = {};
  int calls = 0;
  r = remesh(testshapes::cube(3), o, [&](Stage, double) { return ++calls < 3; });
  CHECK(r.status.code == Code::Cancelled);
}

// Models of ../shared/data that meet every property with the defaults, and (issue 9) a mean
// per-triangle min angle of at least 50 degrees. camelhead.off is slow: it is left to the
// benchmark (bench/models.sh).
TEST_CASE("remesh: shared/data models with the defaults (all but camelhead)") {
  for (const char* name : {"fandisk.off", "3holes.off", "alligator.obj", "blade.off", "face.obj", "spot.obj", "holes.off",
                           "stanford-bunny.obj", "mech-holes-shark.off", "t13_data.stl", "fertility.off"}) {
    ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/" + name));
    RemeshOptions o;
    o.hausdorffSamples = 5000;
    RemeshResult r = checkRemesh(rr.mesh, o, name, false);
    INFO(name);
    CHECK(r.report.optimizeMoves > 0);
    CHECK(r.report.meanMinAngle >= 50.0);
  }
}

// Organic models with many thin features and spikes: the count the sizing field asks for (issue
// 19: within [0.75, 1.33] of the estimate; man was at 1.44 with the refinement at 32 degrees,
// docs/decisions/0045), the bound held, a mean min angle of at least 50 degrees.
TEST_CASE("remesh: man, armadillo and ChineseDragon-10kv with the defaults: the estimated count, the bound") {
  for (const char* name : {"man.off", "armadillo.off", "ChineseDragon-10kv.off"}) {
    ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/" + name));
    RemeshOptions o;
    o.hausdorffSamples = 5000;
    const RemeshResult r = checkRemesh(rr.mesh, o, name, false);
    INFO(std::string(name) << ": " << r.report.triangles << " triangles, estimate " << r.report.estimatedTriangles);
    CHECK(double(r.report.triangles) <= 1.33 * r.report.estimatedTriangles);
    CHECK(double(r.report.triangles) >= 0.75 * r.report.estimatedTriangles);
    CHECK(r.report.meanMinAngle >= 50.0);
  }
}

// At 35 degrees the planar refinement stays at its cheaper bound but for the triangles the
// optimization cannot move, and the optimization lifts the others (docs/decisions/0026): the
// bound holds outside exempt corners, with at most 1.8 times the triangles of the 30 degree run.
TEST_CASE("remesh: a 35 degree bound holds, without the count of a 35 degree planar refinement") {
  checkRemesh(testshapes::cube(4), [] {
    RemeshOptions o;
    o.minAngle = 35;
    o.targetEdgeLengthRel = 0.05;
    o.hausdorffSamples = 2000;
    return o;
  }(), "cube at 35 degrees");
  // camelhead: curves between two exempt corners, whose wedges the plane leaves as the certificate
  // does only when each point takes the corner of its own wedge (cornerChains); its bound is not
  // asserted: two triangles at 33 degrees a few samples from its 0.6 degree corners stay below
  // (issue 22). ChineseDragon-10kv: after two certificate rounds without progress the repair
  // leaves a cut sample's corner below the bound, so the rounds go on (meshRounds' repairLeft).
  for (const char* name : {"fandisk.off", "blade.off", "spot.obj", "mech-holes-shark.off", "camelhead.off", "ChineseDragon-10kv.off"}) {
    ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/" + name));
    RemeshOptions o;
    o.hausdorffSamples = 2000;
    const size_t at30 = remesh(rr.mesh, o).report.triangles;
    o.minAngle = 35;
    RemeshResult r = checkRemesh(rr.mesh, o, name, false, std::string(name) != "camelhead.off");
    INFO(name);
    MESSAGE(std::string(name) << ": " << at30 << " triangles at 30 degrees, " << r.report.triangles << " at 35");
    CHECK(double(r.report.triangles) <= 1.8 * double(at30));
  }
}

// camel at a 30 degree feature angle has a spike where two patches each closed the same corner
// wedge with one triangle (the stitched surface not manifold there), again after every required
// point inside it until the patch kept its boundary as it was.
TEST_CASE("remesh: a corner wedge two patches close alike is opened (camel, feature angle 30)") {
  ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/camel.off"));
  RemeshOptions o;
  o.featureAngle = 30;
  o.hausdorffSamples = 2000;
  checkRemesh(rr.mesh, o, "camel.off at 30 degrees", false, false);
}

// ALSTOM_TEST4 (coarse CAD) at 35° takes two certificate rounds at some targets; capped at one,
// the repair lifts what the second would have: every stage of the table runs, in its order. Which
// targets do depends on the whole pipeline: the first that does is checked, and one must.
TEST_CASE("remesh: progress comes in the stage table's order, and the report times every stage") {
  ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/ALSTOM_TEST4.off"));
  RemeshOptions o;
  o.minAngle = 35;
  o.maxCertificateRounds = 1;
  o.computeHausdorff = false;
  std::vector<Stage> reported;
  RemeshResult r;
  for (const double target : {0.05, 0.03, 0.02, 0.04}) {
    o.targetEdgeLengthRel = target;
    reported.clear();
    r = remesh(rr.mesh, o, [&](Stage s, double f) {
      CHECK(f >= 0);
      CHECK(f <= 1);
      if (reported.empty() || reported.back() != s) reported.push_back(s);
      return true;
    });
    REQUIRE(r.status.ok());
    if (r.report.certificateRounds > 0 && r.report.repairMoves > 0) break;
  }
  REQUIRE(r.report.certificateRounds > 0);
  REQUIRE(r.report.repairMoves > 0);
  for (size_t i = 1; i < reported.size(); ++i) CHECK(int(reported[i - 1]) < int(reported[i]));
  // a stage of weight 0 reports no progress of its own (lift runs inside refine, per patch;
  // precondition between prepare's two segmentations); every other one does
  for (Stage s : kRemeshStages)
    if (stageWeight(s) > 0) CHECK_MESSAGE(std::find(reported.begin(), reported.end(), s) != reported.end(), stageName(s));
  double sum = 0;
  for (Stage s : kRemeshStages) {
    CHECK(*r.report.seconds.of(s) >= 0);
    sum += *r.report.seconds.of(s);
  }
  CHECK(*r.report.seconds.of(Stage::Precondition) > 0);
  CHECK(*r.report.seconds.of(Stage::Certificate) > 0);
  CHECK(*r.report.seconds.of(Stage::Repair) > 0);
  CHECK(sum == doctest::Approx(r.report.seconds.total).epsilon(1e-9));
  CHECK(r.report.seconds.of(Stage::Read) == nullptr);
}

TEST_CASE("remesh: returnPatches gives each patch's planar mesh, consistent with the output") {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.05;
  o.computeHausdorff = false;
  o.patches = true;
  const MeshBuffers in = testshapes::cylinder(48, 12, 6);
  RemeshResult r = remesh(in, o);
  REQUIRE(r.status.ok());
  REQUIRE(r.patches.size() == r.report.patches);
  REQUIRE(r.patchOfTriangle.size() == r.mesh.triangleCount());
  std::vector<size_t> next(r.patches.size(), 0);
  for (size_t t = 0; t < r.mesh.triangleCount(); ++t) {
    const RemeshPatch& p = r.patches[r.patchOfTriangle[t]];
    const size_t k = next[r.patchOfTriangle[t]]++;
    REQUIRE(3 * k + 2 < p.triangles.size());
    for (int c = 0; c < 3; ++c) CHECK(p.outputVertex[p.triangles[3 * k + c]] == r.mesh.triangles[3 * t + c]);
    // counter-clockwise in the plane
    const double* a = &p.uv[2 * p.triangles[3 * k]];
    const double* b = &p.uv[2 * p.triangles[3 * k + 1]];
    const double* c = &p.uv[2 * p.triangles[3 * k + 2]];
    CHECK((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0);
  }
  std::vector<uint8_t> covered(in.triangleCount(), 0);
  for (size_t i = 0; i < r.patches.size(); ++i) {
    const RemeshPatch& p = r.patches[i];
    CHECK(next[i] * 3 == p.triangles.size());
    CHECK(p.layoutUv.size() == 2 * p.layoutFactor.size());
    CHECK(p.layoutTriangles.size() == 3 * p.layoutInputFace.size());
    for (uint32_t f : p.layoutInputFace) {
      REQUIRE(f < in.triangleCount());
      covered[f] = 1;
    }
  }
  // the patches cover the input (whose triangles may be split where their edges are longer than
  // twice the target, mesh/precondition.h)
  CHECK(std::count(covered.begin(), covered.end(), uint8_t(0)) == 0);
}

TEST_CASE("remesh: every boundary condition tried first gives a valid remesh of the cube") {
  for (auto bc : {BoundaryCondition::Free, BoundaryCondition::Corners, BoundaryCondition::Circle}) {
    RemeshOptions o;
    o.targetEdgeLengthRel = 0.05;
    o.hausdorffSamples = 2000;
    o.boundary = bc;
    INFO("boundary " << int(bc));
    RemeshResult r = checkRemesh(testshapes::cube(4), o, "cube", true, bc == BoundaryCondition::Free);
    // flat square faces: the corner-preserving and the free conditions agree, the disk distorts
    if (bc != BoundaryCondition::Circle) CHECK(r.report.trianglesBelowBoundOutsideExempt == 0);
  }
}

namespace {
// A flat isosceles triangle with a `apexDeg` apex at the origin, subdivided `levels` times (each
// triangle into four): an open surface whose boundary curves meet at a small angle at the apex.
MeshBuffers knife(double apexDeg, int levels) {
  const double h = std::tan(apexDeg * 3.14159265358979323846 / 360.0);
  std::vector<std::array<double, 2>> P = {{0, 0}, {1, -h}, {1, h}};
  std::vector<std::array<uint32_t, 3>> T = {{0, 1, 2}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto m = [&](uint32_t a, uint32_t b) {
      auto k = std::minmax(a, b);
      auto it = mid.find({k.first, k.second});
      if (it != mid.end()) return it->second;
      P.push_back({0.5 * (P[a][0] + P[b][0]), 0.5 * (P[a][1] + P[b][1])});
      return mid[{k.first, k.second}] = uint32_t(P.size() - 1);
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (auto t : T) {
      uint32_t ab = m(t[0], t[1]), bc = m(t[1], t[2]), ca = m(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    T = next;
  }
  MeshBuffers mb;
  for (auto p : P) mb.positions.insert(mb.positions.end(), {p[0], p[1], 0.0});
  for (auto t : T) mb.triangles.insert(mb.triangles.end(), t.begin(), t.end());
  return mb;
}
}  // namespace

TEST_CASE("remesh: a 10 degree corner is exempt with its own triangles only (touching it or across its wedge)") {
  const MeshBuffers in = knife(10.0, 5);
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.03;
  o.hausdorffSamples = 2000;
  RemeshResult r = checkRemesh(in, o, "knife", false);
  REQUIRE(r.report.exemptCorners.size() == 1);
  const ExemptCorner& ec = r.report.exemptCorners[0];
  CHECK(ec.vertex == 0);
  CHECK(ec.angle == doctest::Approx(10.0).epsilon(1e-6));
  REQUIRE_FALSE(ec.triangles.empty());
  const MeshBuffers& m = r.mesh;
  auto P = [&](uint32_t v) { return std::array<double, 3>{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; };
  const auto apex = P(ec.outputVertex);
  CHECK(apex[0] == 0.0);
  CHECK(apex[1] == 0.0);
  size_t skinny = 0;
  for (uint32_t t : ec.triangles) {
    const uint32_t* tv = &m.triangles[3 * t];
    bool touches = tv[0] == ec.outputVertex || tv[1] == ec.outputVertex || tv[2] == ec.outputVertex;
    // else an edge of it is seen from the apex under [5, 30) degrees, ends within a factor 2 in distance
    bool across = false;
    for (int c = 0; c < 3 && !touches; ++c) {
      auto a = P(tv[c]), b = P(tv[(c + 1) % 3]);
      double ax = a[0] - apex[0], ay = a[1] - apex[1], bx = b[0] - apex[0], by = b[1] - apex[1];
      double la = std::hypot(ax, ay), lb = std::hypot(bx, by);
      double seen = std::atan2(std::abs(ax * by - ay * bx), ax * bx + ay * by) * 180 / 3.14159265358979323846;
      across = across || (la <= 2 * lb && lb <= 2 * la && seen >= 5.0 - 1e-9 && seen < 30.0);
    }
    CHECK((touches || across));
    skinny += quality::angleStats(MeshBuffers{{P(tv[0])[0], P(tv[0])[1], 0, P(tv[1])[0], P(tv[1])[1], 0, P(tv[2])[0], P(tv[2])[1], 0}, {0, 1, 2}, {}}).minAngle < 30;
  }
  MESSAGE("knife: " << ec.triangles.size() << " exempt triangles (" << skinny << " below 30 deg) of " << m.triangleCount());
}

// A flat disk whose centre, vertex 0, is where three user curves meet: wedges of 22° (an exempt
// corner), 31° and 307°. The 31° wedge is above the 3D bound but below the refinement's planar
// one (the bound plus its margin): its triangles must hold the bound, not be left as the 22°
// wedge's are (spot's seams at the page's defaults met there at 30.8° and 21.7°).
TEST_CASE("remesh: a wedge above the bound beside an exempt one at the same corner holds the bound") {
  testshapes::Builder b;
  const double pi = 3.14159265358979323846;
  std::vector<double> rays = {0.0, 22.0, 53.0};
  for (int i = 1; i < 10; ++i) rays.push_back(53.0 + 307.0 * i / 10);
  const int rings = 12;
  auto at = [&](int k, size_t i) {
    const double r = double(k) / rings, a = rays[i % rays.size()] * pi / 180;
    return b.vertex(r * std::cos(a), r * std::sin(a), 0.0);
  };
  const uint32_t centre = at(0, 0);
  for (size_t i = 0; i < rays.size(); ++i) b.tri(centre, at(1, i), at(1, i + 1));
  for (int k = 1; k < rings; ++k)
    for (size_t i = 0; i < rays.size(); ++i) {
      b.tri(at(k, i), at(k + 1, i), at(k + 1, i + 1));
      b.tri(at(k, i), at(k + 1, i + 1), at(k, i + 1));
    }
  // before the rule both targets left a triangle of 24.3° there, at every certificate round
  for (double target : {0.02, 0.04}) {
    RemeshOptions o;
    o.targetEdgeLengthRel = target;
    o.hausdorffSamples = 2000;
    for (size_t i = 0; i < 3; ++i)
      for (int k = 0; k < rings; ++k) o.featureEdges.push_back({at(k, i), at(k + 1, i)});
    RemeshResult r = checkRemesh(b.m, o, "three rays", false);
    REQUIRE(r.report.exemptCorners.size() == 1);
    CHECK(r.report.exemptCorners[0].vertex == centre);
    CHECK(r.report.exemptCorners[0].angle == doctest::Approx(22.0).epsilon(1e-6));
    // every triangle in the 31° wedge (centroid at a polar angle in (22°, 53°)) holds the bound
    const MeshBuffers& m = r.mesh;
    size_t inWedge = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      double cx = 0, cy = 0;
      for (int c = 0; c < 3; ++c)
        cx += m.positions[3 * m.triangles[3 * t + c]] / 3, cy += m.positions[3 * m.triangles[3 * t + c] + 1] / 3;
      const double polar = std::atan2(cy, cx) * 180 / pi;
      if (!(polar > 22.0 && polar < 53.0)) continue;
      ++inWedge;
      MeshBuffers one{{}, {0, 1, 2}, {}};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) one.positions.push_back(m.positions[3 * m.triangles[3 * t + c] + k]);
      CHECK(quality::angleStats(one).minAngle >= o.minAngle - 1e-9);
    }
    CHECK(inWedge > 10);
  }
}

TEST_CASE("remesh: a ramp winding two and a half turns is split where its flat map overlaps, the bound held") {
  // Flattened whole, the ramp's border crosses itself a turn apart; the splits go on until no
  // part winds a full turn.
  const MeshBuffers ramp = testshapes::helicoidStrip(2.5, 1.0, 2.0, 0.3, 150, 8);
  RemeshOptions o;
  o.threads = 1;
  const RemeshResult r = remesh(ramp, o);
  REQUIRE(r.status.ok());
  CHECK(r.report.patchSplitsForScale >= 2);  // three parts at least
  CHECK(r.report.patches <= 5);              // two per turn at most
  CHECK(r.report.minAngle >= o.minAngle);
  CHECK(r.report.topologyPreserved);
}

// A crease that ends inside a region (FeatureOptions::innerCreases) is a constrained polyline in
// its patch's planar domain: a flat square with three such chains is one patch, every chain is
// made of output edges (the optimization neither flips nor splits them), and the bound holds.
TEST_CASE("remesh: creases ending inside a flat square stay inside its one patch") {
  const int n = 20;
  testshapes::Builder b;
  auto at = [&](int i, int j) { return b.vertex(double(i) / n, double(j) / n, 0); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      b.tri(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      b.tri(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.03;
  o.hausdorffSamples = 2000;
  for (int i = 6; i < 14; ++i) o.featureEdges.push_back({at(i, 10), at(i + 1, 10)});  // inside, straight
  for (int i = 0; i < 8; ++i) o.featureEdges.push_back({at(i, 4), at(i + 1, 4)});     // from the border in
  for (int i = 12; i < 16; ++i) o.featureEdges.push_back({at(i, 15), at(i + 1, 15)});  // an L inside
  for (int j = 15; j < 18; ++j) o.featureEdges.push_back({at(16, j), at(16, j + 1)});
  o.innerCreases = true;
  const RemeshResult inner = checkRemesh(b.m, o, "inner creases");
  CHECK(inner.report.patches == 1);
  CHECK(inner.report.featureCurves >= 4);  // the border, the three chains (the L's corner parts it)
  // each chain's input vertices are output vertices joined by output edges along the chain
  std::set<std::pair<long long, long long>> onChain;
  for (size_t t = 0; t < inner.mesh.triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const uint32_t u = inner.mesh.triangles[t + c], v = inner.mesh.triangles[t + (c + 1) % 3];
      const double* p = &inner.mesh.positions[3 * size_t(u)];
      const double* q = &inner.mesh.positions[3 * size_t(v)];
      if (std::abs(p[1] - 0.5) < 1e-12 && std::abs(q[1] - 0.5) < 1e-12)
        onChain.insert({std::llround(std::min(p[0], q[0]) * 1e9), std::llround(std::max(p[0], q[0]) * 1e9)});
    }
  double covered = 0;
  for (const auto& [lo, hi] : onChain) covered += double(hi - lo) * 1e-9;
  CHECK(covered == doctest::Approx(0.4).epsilon(1e-9));
  // without: each chain is continued until it closes a part off
  o.innerCreases = false;
  const RemeshResult closed = checkRemesh(b.m, o, "creases continued");
  CHECK(closed.report.patches > 1);
}

// ChineseDragon-10kv: its creases as detected close one region; continued from their ends they
// close 63 (73 patches after flattening). Kept inside their patches they cut nothing.
TEST_CASE("remesh: ChineseDragon-10kv with inner creases: fewer patches, every curve kept, the bound held") {
  ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/ChineseDragon-10kv.off"));
  RemeshOptions o;
  o.hausdorffSamples = 5000;
  o.innerCreases = true;
  const RemeshResult r = checkRemesh(rr.mesh, o, "ChineseDragon-10kv inner", false);
  CHECK(r.report.patches <= 64);
  CHECK(r.report.featureCurves > 50);
  CHECK(r.report.meanMinAngle >= 50.0);
}

// The cuts the flattening makes (inner creases closed, sink, spike and split cuts) leave narrow
// patches beside older cuts; once every patch is flattened they are joined to a neighbour, two at
// a time, and a joined patch flattened worse than its parts is taken apart again. man had 79
// patches (26 of them under 60 faces), camel 56.
TEST_CASE("remesh: man and camel at the defaults: narrow patches joined, at most 64 patches, the bound held") {
  for (const char* name : {"man.off", "camel.off"}) {
    CAPTURE(name);
    ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/" + name));
    RemeshOptions o;
    o.hausdorffSamples = 5000;
    const RemeshResult r = checkRemesh(rr.mesh, o, name, false);
    CHECK(r.report.patchJoins > 0);
    CHECK(r.report.patches <= 64);
    CHECK(r.report.meanMinAngle >= 50.0);
    CHECK(r.report.triangles <= 1.33 * r.report.estimatedTriangles);
  }
}

// elk at a 20° feature angle: a patch with twelve inner curves, four of them meeting at a saddle
// (angle sum 432°, 35° between two of them) whose flattening shrinks those wedges. The triangles
// there have three curve samples: the optimization must be free to split a chord between two
// curves (only the curves' own segments are kept), and each sample's planar point must pull back
// onto the sample (the edges kept in the flattening, the projective map along them), or the
// certificate rounds shrink those triangles round after round.
TEST_CASE("remesh: elk at a 20 degree feature angle with inner creases holds the bound") {
  ReadResult rr = readMesh(test::readFile(std::string(CONFORMESH_DATA_DIR) + "/elk.off"));
  RemeshOptions o;
  o.hausdorffSamples = 5000;
  o.innerCreases = true;
  o.featureAngle = 20;
  o.targetEdgeLengthRel = 0.02;
  const RemeshResult r = checkRemesh(rr.mesh, o, "elk inner 20", false);
  CHECK(r.report.meanMinAngle >= 50.0);
  CHECK(double(r.report.triangles) <= 1.33 * r.report.estimatedTriangles);
}
