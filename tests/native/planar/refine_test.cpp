#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "planar/refine.h"
#include "planar_test_util.h"

using namespace planar_test;

namespace {
double longestEdge(const PlanarMesh& m, size_t t) {
  double l = 0;
  for (int i = 0; i < 3; ++i) {
    const double* a = P(m, m.triangles[3 * t + i]);
    const double* b = P(m, m.triangles[3 * t + (i + 1) % 3]);
    l = std::max(l, std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  return l;
}
double triArea(const PlanarMesh& m, size_t t) {
  const double* p = P(m, m.triangles[3 * t]);
  const double* q = P(m, m.triangles[3 * t + 1]);
  const double* r = P(m, m.triangles[3 * t + 2]);
  return 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
}
}  // namespace

TEST_CASE("refinement of the data PSLGs meets the angle bound at 20.7, 26, 30, 33 degrees") {
  for (const char* name : {"square_holes", "wiggly5000", "alligator_s3_lscm"}) {
    Pslg in = loadPoly(name);
    double inputArea = meshArea(triangulatePslg(in));
    for (double theta : {20.7, 26.0, 30.0, 33.0}) {
      CAPTURE(name);
      CAPTURE(theta);
      RefineOptions o;
      o.minAngleDeg = theta;
      RefineResult r = refinePslg(in, o);
      CHECK(r.status.ok());
      MeshCheck c = checkMesh(r.mesh, in, true);
      CHECK(c.inverted == 0);
      CHECK(c.nonManifold == 0);
      CHECK(c.notDelaunay == 0);
      CHECK(c.segmentsBroken == 0);
      CHECK(c.inputMissing == 0);
      CHECK(c.paramOff == 0);
      CHECK(c.belowAngle(r.mesh, theta) <= r.exemptTriangles);
      CHECK(r.minAngleDeg >= theta);
      CHECK(std::fabs(meshArea(r.mesh) - inputArea) <= 1e-9 * std::fabs(inputArea));
      for (size_t v = 0; v < in.points.size(); ++v) CHECK(r.mesh.points[v] == in.points[v]);
    }
  }
}

// Triangles whose three vertices lie on segments (ends of constrained edges), and how many of
// them have a smaller angle than theta.
size_t segmentTrianglesBelow(const PlanarMesh& m, double theta, size_t* total = nullptr) {
  std::vector<uint8_t> on(m.vertexCount(), 0);
  for (size_t e = 0; e < m.edgeSegment.size(); ++e)
    if (m.edgeSegment[e] >= 0) on[m.edges[2 * e]] = on[m.edges[2 * e + 1]] = 1;
  size_t below = 0, n = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* v = &m.triangles[3 * t];
    if (!(on[v[0]] && on[v[1]] && on[v[2]])) continue;
    ++n;
    if (triMinAngleDeg(P(m, v[0]), P(m, v[1]), P(m, v[2])) < theta) ++below;
  }
  if (total) *total = n;
  return below;
}

// A strip between two sampled sides, the samples of one side halfway between those of the other:
// triangles across it have their three vertices on segments and a smallest angle of ~33 degrees.
Pslg sampledStrip() {
  Pslg in;
  const double h = 0.081, b = 0.25;
  for (int i = 0; i <= 16; ++i) in.points.insert(in.points.end(), {i * b, 0});
  in.points.insert(in.points.end(), {4, h});
  for (int i = 15; i >= 0; --i) in.points.insert(in.points.end(), {(i + 0.5) * b, h});
  in.points.insert(in.points.end(), {0, h});
  const uint32_t n = uint32_t(in.points.size() / 2);
  for (uint32_t v = 0; v < n; ++v) in.segments.insert(in.segments.end(), {v, (v + 1) % n});
  return in;
}

TEST_CASE("segment triangles: a higher bound for the triangles with their three vertices on segments") {
  const Pslg in = sampledStrip();
  RefineOptions o;
  o.minAngleDeg = 30;
  o.diametralLens = true;  // circles would split the sides: no triangle would span the strip
  const RefineResult plain = refinePslg(in, o);
  size_t total = 0;
  // without the option most of them are between the two bounds: the test can tell
  CHECK(segmentTrianglesBelow(plain.mesh, 37.0, &total) > plain.exemptTriangles + 10);
  o.segmentTriangleMinAngleDeg = 37;
  const RefineResult r = refinePslg(in, o);
  CHECK(r.status.ok());
  const MeshCheck c = checkMesh(r.mesh, in, true);
  CHECK(c.inverted == 0);
  CHECK(c.notDelaunay == 0);
  CHECK(c.segmentsBroken == 0);
  CHECK(c.paramOff == 0);
  CHECK(r.minAngleDeg >= 30.0);
  CHECK(segmentTrianglesBelow(r.mesh, 37.0) <= r.exemptTriangles);
  MESSAGE("strip: " << plain.mesh.triangleCount() << " -> " << r.mesh.triangleCount() << " triangles");
}

TEST_CASE("Steiner economy: wiggly5000 at 30 degrees, no size bound, at most 52,000 triangles") {
  RefineResult r = refinePslg(loadPoly("wiggly5000"));
  CHECK(r.mesh.triangleCount() <= 52000);
  CHECK(r.minAngleDeg >= 30.0);
}

TEST_CASE("size bounds: max area, max edge, sizing callback, per-vertex sizes") {
  Pslg in = loadPoly("square_holes");
  {
    RefineOptions o;
    o.maxArea = 2e-4;
    RefineResult r = refinePslg(in, o);
    for (size_t t = 0; t < r.mesh.triangleCount(); ++t) CHECK(triArea(r.mesh, t) <= o.maxArea);
    CHECK(r.minAngleDeg >= 30.0);
  }
  {
    RefineOptions o;
    o.maxEdge = 0.02;
    RefineResult r = refinePslg(in, o);
    for (size_t t = 0; t < r.mesh.triangleCount(); ++t) CHECK(longestEdge(r.mesh, t) <= o.maxEdge);
  }
  {
    RefineOptions o;
    o.sizing = [](double x, double y) { return 0.005 + 0.05 * std::hypot(x - 0.5, y - 0.5); };
    RefineResult r = refinePslg(in, o);
    size_t bad = 0;
    for (size_t t = 0; t < r.mesh.triangleCount(); ++t) {
      const uint32_t* v = &r.mesh.triangles[3 * t];
      double cx = (P(r.mesh, v[0])[0] + P(r.mesh, v[1])[0] + P(r.mesh, v[2])[0]) / 3;
      double cy = (P(r.mesh, v[0])[1] + P(r.mesh, v[1])[1] + P(r.mesh, v[2])[1]) / 3;
      if (longestEdge(r.mesh, t) > o.sizing(cx, cy)) ++bad;
    }
    CHECK(bad == 0);
    CHECK(r.minAngleDeg >= 30.0);
  }
  {
    RefineOptions o;
    o.vertexSizing.assign(in.points.size() / 2, 0.03);
    RefineResult r = refinePslg(in, o);
    for (size_t t = 0; t < r.mesh.triangleCount(); ++t) CHECK(longestEdge(r.mesh, t) <= 0.03 * (1 + 1e-12));
  }
}

TEST_CASE("small input angles: refinement terminates, exempt triangles are counted") {
  // A 10-degree wedge and a 5-degree spike meeting an interior segment.
  Pslg in;
  const double d2r = 3.14159265358979323846 / 180;
  in.points = {0, 0, 1, 0, std::cos(10 * d2r), std::sin(10 * d2r), -1, 1, -1, -1, 0.5, 0.5 * std::tan(5 * d2r)};
  in.segments = {0, 1, 1, 2, 2, 0, 0, 5, 0, 3, 3, 4, 4, 0};
  for (double theta : {20.7, 30.0, 33.0}) {
    CAPTURE(theta);
    RefineOptions o;
    o.minAngleDeg = theta;
    o.maxInsertions = 200000;
    RefineResult r = refinePslg(in, o);
    CHECK(r.status.ok());
    CHECK(r.exemptTriangles > 0);
    CHECK(r.minAngleDeg >= theta);
    MeshCheck c = checkMesh(r.mesh, in, true);
    CHECK(c.inverted == 0);
    CHECK(c.segmentsBroken == 0);
    CHECK(c.belowAngle(r.mesh, theta) <= r.exemptTriangles);
  }
}

TEST_CASE("insertion cap, cancel and bad options") {
  Pslg in = loadPoly("square_holes");
  RefineOptions o;
  o.maxInsertions = 10;
  RefineResult r = refinePslg(in, o);
  CHECK(r.status.code == Code::IterationLimit);
  CHECK(r.insertions == 10);
  CHECK(checkMesh(r.mesh, in, true).inverted == 0);

  RefineOptions c;
  c.maxArea = 1e-6;
  int calls = 0;
  c.progress = [&](Stage, double) { return ++calls < 3; };
  Code code = Code::Ok;
  try {
    refinePslg(in, c);
  } catch (const Error& e) {
    code = e.code();
  }
  CHECK(code == Code::Cancelled);

  for (double bad : {-1.0, 35.0, std::nan(""), -2.0, 41.0}) {
    RefineOptions b;
    b.minAngleDeg = bad;
    if (bad == -2.0 || bad == 41.0) b.minAngleDeg = 30, b.segmentTriangleMinAngleDeg = bad;  // its range is [0, 40]
    Code k = Code::Ok;
    try {
      refinePslg(in, b);
    } catch (const Error& e) {
      k = e.code();
    }
    CHECK(k == Code::InvalidArgument);
  }
}

// Random inputs with small angles (spikes) between 20.7 and 30 degrees. (At 33 degrees about
// 5% of such inputs keep a few non-exempt triangles below the bound next to a small input
// angle: reported through minAngleDeg, see refine.h.)
TEST_CASE("random star polygons with sharp spikes, holes and interior segments") {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> U(0, 1);
  for (int iter = 0; iter < 60; ++iter) {
    CAPTURE(iter);
    Pslg in;
    int n = 5 + int(U(rng) * 40);
    for (int i = 0; i < n; ++i) {
      double a = 2 * 3.14159265358979323846 * (i + 0.8 * U(rng)) / n;
      double r = 0.2 + U(rng);
      in.points.insert(in.points.end(), {r * std::cos(a), r * std::sin(a)});
      in.segments.insert(in.segments.end(), {uint32_t(i), uint32_t((i + 1) % n)});
    }
    // a small square hole at the center and an interior segment from it
    uint32_t b = uint32_t(n);
    double h = 0.02 + 0.05 * U(rng);
    in.points.insert(in.points.end(), {-h, -h, h, -h, h, h, -h, h});
    in.segments.insert(in.segments.end(), {b, b + 1, b + 1, b + 2, b + 2, b + 3, b + 3, b});
    in.holes = {0, 0};
    in.points.insert(in.points.end(), {0.1 + 0.05 * U(rng), 0.02 + 0.1 * U(rng)});
    in.segments.insert(in.segments.end(), {b + 2, b + 4});
    RefineOptions o;
    o.minAngleDeg = iter % 2 ? 30.0 : 20.7;
    o.maxInsertions = 500000;
    if (iter % 3 == 0) o.maxArea = 1e-3;
    RefineResult r;
    Code code = Code::Ok;
    try {
      r = refinePslg(in, o);
    } catch (const Error& e) {
      code = e.code();  // a random polygon may self-intersect: only InvalidPslg is acceptable
    }
    if (code != Code::Ok) {
      CHECK(code == Code::InvalidPslg);
      continue;
    }
    CHECK(r.status.ok());
    MeshCheck c = checkMesh(r.mesh, in, true);
    CHECK(c.inverted == 0);
    CHECK(c.nonManifold == 0);
    CHECK(c.notDelaunay == 0);
    CHECK(c.segmentsBroken == 0);
    CHECK(c.paramOff == 0);
    CHECK(r.minAngleDeg >= o.minAngleDeg);
    CHECK(c.belowAngle(r.mesh, o.minAngleDeg) <= r.exemptTriangles);
  }
}

TEST_CASE("apexOf: a chain is not split for the points of the other chain of its apex, so a narrower wedge needs no more triangles") {
  // A wedge of angle w with one side sampled at 1/4, 1/2, 1, the other at 0.35, 0.7, 1 (the
  // samples of the two patches' curves do not face each other), closed by the chord between the
  // far ends. Plain Ruppert splits each side where the other side encroaches upon it, down to
  // pieces about as long as the wedge is wide there: a count that grows like 1 / w. With the
  // sides as chains of the apex the triangles across the wedge are left, whatever w.
  const double d2r = 3.14159265358979323846 / 180;
  const auto wedge = [&](double w, bool chains) {
    const std::vector<double> dist[2] = {{0.25, 0.5, 1.0}, {0.35, 0.7, 1.0}};
    Pslg in;
    in.points = {0, 0};
    for (int k = 0; k < 2; ++k)
      for (double d : dist[k]) in.points.insert(in.points.end(), {d * std::cos(k * w * d2r), d * std::sin(k * w * d2r)});
    in.segments = {0, 1, 1, 2, 2, 3, 3, 6, 6, 5, 5, 4, 4, 0};
    RefineOptions o;
    o.minAngleDeg = 30;
    o.minSegmentLength = 1e-9;
    if (chains) {
      o.apexOf = {kNoApex, 0, 0, 0, 0, 0, 0};
      o.chainOf = {kNoApex, 0, 0, 0, 1, 1, 1};
    }
    const RefineResult r = refinePslg(in, o);
    REQUIRE(r.status.ok());
    CHECK((r.minAngleDeg >= 30 || r.exemptTriangles == r.mesh.triangleCount()));  // 0 when every one is exempt
    const MeshCheck c = checkMesh(r.mesh, in, true);
    CHECK(c.inverted == 0);
    CHECK(c.segmentsBroken == 0);
    CHECK(c.belowAngle(r.mesh, 30) <= r.exemptTriangles);
    return r.mesh.triangleCount();
  };
  const size_t plain2 = wedge(2, false), plainHalf = wedge(0.5, false);
  const size_t chained2 = wedge(2, true), chainedHalf = wedge(0.5, true);
  MESSAGE("triangles at 2 and 0.5 degrees: plain " << plain2 << ", " << plainHalf << "; chains " << chained2 << ", " << chainedHalf);
  CHECK(plainHalf > 2 * plain2);
  CHECK(2 * chainedHalf < 3 * chained2);
  CHECK(2 * chainedHalf < plainHalf);
}

TEST_CASE("apexOf: the triangles across a small corner whose sides are chains of segments are left as it forces them, round after round") {
  // A 10-degree wedge whose sides are chains of points (a patch's curve samples). As in the
  // remesh's conforming rounds, each round meshes from scratch with the previous round's boundary
  // splits as input points, and the patch across one side takes those up at other distances
  // (its own planar scale, here 7 % more): the concentric shells of one round are not the next
  // round's, so the triangles across the wedge are not exempt by equal distances, and each round
  // refines them again.
  const double d2r = 3.14159265358979323846 / 180;
  const auto rounds = [&](bool chains, size_t& insertions) {
    std::vector<double> side[2] = {{0.13, 0.31, 0.55, 1.0}, {0.2, 0.45, 0.7, 1.0}};
    const double dir[2][2] = {{1, 0}, {std::cos(10 * d2r), std::sin(10 * d2r)}};
    insertions = 0;
    double nearest = INFINITY;
    for (int round = 0; round < 6; ++round) {
      Pslg in;
      in.points = {0, 0};
      for (int k = 0; k < 2; ++k)
        for (double d : side[k]) in.points.insert(in.points.end(), {d * dir[k][0], d * dir[k][1]});
      const uint32_t n0 = uint32_t(side[0].size()), n1 = uint32_t(side[1].size());
      in.segments = {0, 1};
      for (uint32_t i = 1; i < n0; ++i) in.segments.insert(in.segments.end(), {i, i + 1});
      in.segments.insert(in.segments.end(), {n0, n0 + n1});
      for (uint32_t i = n0 + n1; i > n0 + 1; --i) in.segments.insert(in.segments.end(), {i, i - 1});
      in.segments.insert(in.segments.end(), {n0 + 1, 0});
      RefineOptions o;
      o.minAngleDeg = 30;
      o.minSegmentLength = 1e-6;
      if (chains) {
        o.apexOf.assign(in.points.size() / 2, kNoApex);
        o.chainOf.assign(in.points.size() / 2, kNoApex);
        for (uint32_t i = 1; i <= n0 + n1; ++i) o.apexOf[i] = 0, o.chainOf[i] = i <= n0 ? 0 : 1;
      }
      const RefineResult r = refinePslg(in, o);
      REQUIRE(r.status.ok());
      CHECK(r.minAngleDeg >= 30);
      const MeshCheck c = checkMesh(r.mesh, in, true);
      CHECK(c.inverted == 0);
      CHECK(c.segmentsBroken == 0);
      CHECK(c.belowAngle(r.mesh, 30) <= r.exemptTriangles);
      insertions += r.insertions;
      // the splits on the two sides join them; the one across side 0 sees them 7 % farther
      bool any = false;
      for (size_t v = in.points.size() / 2; v < r.mesh.vertexCount(); ++v) {
        const int32_t sg = r.mesh.vertexSegment[v];
        if (sg < 0 || uint32_t(sg) == n0) continue;  // interior, or on the far chord
        const int k = uint32_t(sg) < n0 ? 0 : 1;
        const double d = std::hypot(r.mesh.points[2 * v], r.mesh.points[2 * v + 1]) * (k == 0 ? 1.07 : 1.0);
        if (d >= 1.0) continue;
        side[k].push_back(d);
        nearest = std::min(nearest, d);
        any = true;
      }
      for (auto& sd : side) std::sort(sd.begin(), sd.end());
      if (!any) break;
    }
    return std::min({nearest, side[0].front(), side[1].front()});
  };
  size_t plainInsertions = 0, chainedInsertions = 0;
  const double plain = rounds(false, plainInsertions), chained = rounds(true, chainedInsertions);
  MESSAGE("nearest side point to the apex after the rounds: " << plain << " without chains, " << chained << " with; insertions "
                                                             << plainInsertions << ", " << chainedInsertions);
  CHECK(chained >= plain);
  CHECK(2 * chainedInsertions < plainInsertions);
  RefineOptions bad;
  bad.apexOf = {kNoApex};  // one entry for a PSLG of three points
  Pslg tri;
  tri.points = {0, 0, 1, 0, 0, 1};
  tri.segments = {0, 1, 1, 2, 2, 0};
  CHECK_THROWS(refinePslg(tri, bad));
}
