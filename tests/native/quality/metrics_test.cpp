#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/detmath.h"
#include "quality/metrics.h"
#include "quality_test_meshes.h"

using namespace conformesh;
using namespace conformesh::quality;
using quality_test::grid;

namespace {

//! Closed unit cube, 12 triangles, outward orientation.
MeshBuffers cube() {
  MeshBuffers m;
  for (int k = 0; k < 8; ++k) m.positions.insert(m.positions.end(), {double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
  m.triangles = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return m;
}

}  // namespace

TEST_CASE("angle stats: an equilateral triangle has all angles 60°") {
  MeshBuffers m;
  m.positions = {0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0};
  m.triangles = {0, 1, 2};
  AngleStats s = angleStats(m);
  CHECK(s.triangles == 1);
  CHECK(s.degenerateTriangles == 0);
  CHECK(s.minAngle == doctest::Approx(60.0).epsilon(1e-12));
  CHECK(s.maxAngle == doctest::Approx(60.0).epsilon(1e-12));
  CHECK(s.meanMinAngle == doctest::Approx(60.0).epsilon(1e-12));
  CHECK(s.pctBelow30 == 0.0);
}

TEST_CASE("angle stats: right isosceles triangles, a needle and a degenerate triangle") {
  MeshBuffers m = grid(4, [](double, double) { return 0.0; });
  AngleStats s = angleStats(m);
  CHECK(s.minAngle == doctest::Approx(45.0));
  CHECK(s.maxAngle == doctest::Approx(90.0));
  CHECK(s.pctBelow30 == 0.0);

  MeshBuffers bad;
  bad.positions = {0, 0, 0, 1, 0, 0, 0.5, 1e-3, 0, 2, 0, 0};
  bad.triangles = {0, 1, 2, 0, 1, 3};  // a needle (angle ~0.11°) and a collinear (zero-area) one
  AngleStats b = angleStats(bad);
  CHECK(b.degenerateTriangles == 1);
  CHECK(b.minAngle == 0.0);
  CHECK(b.maxAngle == 180.0);
  CHECK(b.pctBelow20 == 100.0);
  CHECK(b.minAngleHistogram[0] == 2);
}

TEST_CASE("angle stats: min and max are those of all three atan2 angles, also for near ties") {
  // random triangles, isosceles and near-isosceles ones, needles and caps: the statistics skip
  // the middle angle when the cosines tell the angles apart, so compare with all three
  MeshBuffers m;
  uint64_t state = 7;
  auto uniform = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * (1.0 / 9007199254740992.0);
  };
  auto add = [&m](std::array<double, 9> p) {
    const uint32_t base = uint32_t(m.positions.size() / 3);
    m.positions.insert(m.positions.end(), p.begin(), p.end());
    m.triangles.insert(m.triangles.end(), {base, base + 1, base + 2});
  };
  for (int i = 0; i < 2000; ++i) {
    const double e = i % 4 == 0 ? 0.0 : std::pow(10.0, -16.0 * uniform());  // tie, or nearly
    const double h = std::pow(10.0, 3.0 - 10.0 * uniform());
    add({0, 0, 0, 2, 0, 0, 1 + e, h, 0.1 * uniform()});
    add({uniform(), uniform(), uniform(), uniform(), uniform(), uniform(), uniform(), uniform(), uniform()});
  }
  add({0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0});
  std::vector<double> triMin;
  const AngleStats s = angleStats(m, &triMin);
  REQUIRE(triMin.size() == m.triangleCount());
  double lo = 180, hi = 0;
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    Vec3 p[3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) p[c][k] = m.positions[3 * m.triangles[3 * f + c] + k];
    double a[3];
    for (int c = 0; c < 3; ++c) {
      const Vec3& o = p[c];
      const Vec3 u{p[(c + 1) % 3][0] - o[0], p[(c + 1) % 3][1] - o[1], p[(c + 1) % 3][2] - o[2]};
      const Vec3 v{p[(c + 2) % 3][0] - o[0], p[(c + 2) % 3][1] - o[1], p[(c + 2) % 3][2] - o[2]};
      const Vec3 x{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      a[c] = dmath::atan2(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
    }
    const double mn = std::min({a[0], a[1], a[2]}), mx = std::max({a[0], a[1], a[2]});
    CHECK(triMin[f] == mn);
    lo = std::min(lo, mn * (180.0 / 3.14159265358979323846));
    hi = std::max(hi, mx * (180.0 / 3.14159265358979323846));
  }
  CHECK(s.degenerateTriangles == 0);
  CHECK(s.minAngle == lo);
  CHECK(s.maxAngle == hi);
}

TEST_CASE("edge stats and topology at once: the same as each alone") {
  MeshBuffers two = cube();
  for (size_t i = 0; i < 24; ++i) two.positions.push_back(two.positions[i] + (i % 3 == 0 ? 5.0 : 0.0));
  for (size_t i = 0; i < 30; ++i) two.triangles.push_back(two.triangles[i] + 8);  // one open cube
  const EdgeTopology et = edgeStatsAndTopology(two);
  const EdgeStats e = edgeStats(two);
  const TopologySummary t = topologySummary(two);
  CHECK(et.edges.edges == e.edges);
  CHECK(et.edges.meanLength == e.meanLength);
  CHECK(et.edges.delaunayFraction == e.delaunayFraction);
  CHECK(et.topology.components == t.components);
  CHECK(et.topology.boundaryLoops == t.boundaryLoops);
  CHECK(et.topology.boundaryLoops == 1);
  CHECK(et.topology.euler == t.euler);
}

TEST_CASE("edge stats: a flat grid split along one diagonal is Delaunay (cocircular ties count)") {
  MeshBuffers m = grid(3, [](double, double) { return 0.0; });
  EdgeStats e = edgeStats(m);
  CHECK(e.edges == size_t(3 * 4 * 2 + 9));
  CHECK(e.minLength == doctest::Approx(1.0 / 3));
  CHECK(e.maxLength == doctest::Approx(std::sqrt(2.0) / 3));
  CHECK(e.delaunayFraction == doctest::Approx(1.0));

  // A thin rhombus split along its long diagonal is not Delaunay.
  MeshBuffers r;
  r.positions = {-1, 0, 0, 0, -0.1, 0, 1, 0, 0, 0, 0.1, 0};
  r.triangles = {0, 1, 2, 0, 2, 3};
  CHECK(edgeStats(r).delaunayFraction == 0.0);
}

TEST_CASE("topology: disk, closed cube, two components, a non-manifold fin") {
  TopologySummary disk = topologySummary(grid(5, [](double, double) { return 0.0; }));
  CHECK(disk.components == 1);
  CHECK(disk.boundaryLoops == 1);
  CHECK(disk.euler == 1);
  CHECK(disk.genus == 0);

  MeshBuffers c = cube();
  TopologySummary ct = topologySummary(c);
  CHECK(ct.euler == 2);
  CHECK(ct.boundaryLoops == 0);
  CHECK(ct.genus == 0);

  // Two disjoint cubes: two components, χ = 4, genus 0.
  MeshBuffers two = c;
  for (size_t i = 0; i < c.positions.size(); ++i) two.positions.push_back(c.positions[i] + (i % 3 == 0 ? 5.0 : 0.0));
  for (uint32_t t : c.triangles) two.triangles.push_back(t + 8);
  TopologySummary tt = topologySummary(two);
  CHECK(tt.components == 2);
  CHECK(tt.euler == 4);
  CHECK(tt.genus == 0);

  // A third triangle on one edge: non-manifold, genus undefined.
  MeshBuffers fin;
  fin.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
  fin.triangles = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  TopologySummary ft = topologySummary(fin);
  CHECK(ft.nonManifoldEdges == 1);
  CHECK(ft.genus == -1);
  CHECK(ft.nonManifoldVertices == 2);  // the fin's ends: three fans each
}

TEST_CASE("topology: non-manifold vertices are bow-ties, none on manifold meshes") {
  CHECK(topologySummary(grid(5, [](double, double) { return 0.0; })).nonManifoldVertices == 0);
  CHECK(topologySummary(cube()).nonManifoldVertices == 0);
  // two triangles touching at vertex 0 only
  MeshBuffers bowtie;
  bowtie.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
  bowtie.triangles = {0, 1, 2, 0, 3, 4};
  const TopologySummary b = topologySummary(bowtie);
  CHECK(b.nonManifoldVertices == 1);
  CHECK(b.nonManifoldEdges == 0);
  // two cubes sharing one corner (the second cube's vertex 0 is the first's vertex 7, at (1, 1, 1))
  MeshBuffers c = cube(), two = c;
  for (size_t i = 0; i < c.positions.size(); ++i) two.positions.push_back(c.positions[i] + 1.0);
  for (uint32_t t : c.triangles) two.triangles.push_back(t == 0 ? 7 : t + 8);
  CHECK(topologySummary(two).nonManifoldVertices == 1);
  CHECK(edgeStatsAndTopology(two).topology.nonManifoldVertices == 1);
}

TEST_CASE("closest point on a triangle: regions and a degenerate triangle") {
  Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  auto near = [](const Vec3& p, const Vec3& q) { return distanceSquared(p, q) < 1e-24; };
  CHECK(near(closestPointOnTriangle({0.2, 0.2, 3}, a, b, c), {0.2, 0.2, 0}));   // face
  CHECK(near(closestPointOnTriangle({-1, -1, 0}, a, b, c), a));                 // vertex
  CHECK(near(closestPointOnTriangle({0.5, -2, 1}, a, b, c), {0.5, 0, 0}));      // edge ab
  CHECK(near(closestPointOnTriangle({1, 1, 0}, a, b, c), {0.5, 0.5, 0}));       // edge bc
  CHECK(near(closestPointOnTriangle({0.5, 1, 0}, a, b, Vec3{2, 0, 0}), {0.5, 0, 0}));  // collinear
}

TEST_CASE("Hausdorff: a mesh to itself is 0; to a translated copy it is the translation") {
  MeshBuffers m = grid(8, [](double x, double y) { return 0.3 * std::sin(3 * x) * std::cos(2 * y); });
  HausdorffOptions opt;
  opt.samplesPerSide = 20000;
  opt.computeMean = true;
  HausdorffResult self = hausdorffDistance(m, m, opt);
  CHECK(self.hausdorff < 1e-12);
  CHECK(self.samplesA >= 20000);

  // A closed surface moved by t along a direction: the sampled distance tends to |t| from below
  // (the farthest points are on faces facing the motion).
  MeshBuffers c = cube();
  MeshBuffers moved = c;
  double t = 0.05;
  for (size_t i = 0; i < moved.positions.size(); i += 3) moved.positions[i] += t;
  HausdorffResult h = hausdorffDistance(moved, c, opt);
  CHECK(h.hausdorff <= t * (1 + 1e-12));
  CHECK(h.hausdorff >= t * (1 - 1e-9));  // cube vertices themselves sit exactly t away
  CHECK(h.relative == doctest::Approx(t / std::sqrt(3.0)));
  CHECK(h.meanAToB > 0);
  CHECK(h.meanAToB < t);

  // Deterministic: same seed, same answer bit for bit.
  HausdorffResult h2 = hausdorffDistance(moved, c, opt);
  CHECK(h2.hausdorff == h.hausdorff);
  CHECK(h2.meanBToA == h.meanBToA);
}

TEST_CASE("feature preservation: a cube keeps its edges; a smooth copy does not") {
  MeshBuffers c = cube();
  FeatureResult same = featurePreservation(c, c);
  CHECK(same.referenceFeatureEdges == 12);  // the 12 cube edges (face diagonals are flat)
  CHECK(same.fractionKept == 1.0);

  // The flat grid has no sharp edge at all: nothing is kept of the cube's features.
  MeshBuffers flat = grid(4, [](double, double) { return 0.0; });
  FeatureResult none = featurePreservation(flat, c);
  CHECK(none.outputFeatureEdges == 0);
  CHECK(none.fractionKept == 0.0);
}

TEST_CASE("edge stats: the Delaunay count of one edge agrees with the sum of its two opposite angles") {
  // Two triangles (a, b, c) and (b, a, d) on the edge ab, with c and d at random 3D places
  // (acute, right, obtuse and near-degenerate opposite angles; folded pairs too). The edge is
  // locally Delaunay when the angles at c and d sum to at most π, computed here independently
  // with acos; pairs within 1e-9 of π are ties and skipped (the grid test covers ties).
  uint64_t state = 0x9e3779b97f4a7c15ull;
  auto uniform = [&](double lo, double hi) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * double(state >> 11) / double(1ull << 53);
  };
  auto angleAt = [](const std::array<double, 3>& p, const std::array<double, 3>& q, const std::array<double, 3>& r) {
    double u[3], w[3];
    for (int k = 0; k < 3; ++k) u[k] = q[k] - p[k], w[k] = r[k] - p[k];
    const double d = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), nw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    return std::acos(std::clamp(d / (nu * nw), -1.0, 1.0));
  };
  int delaunay = 0, not_ = 0;
  for (int i = 0; i < 4000; ++i) {
    const std::array<double, 3> a{-1, 0, 0}, b{1, 0, 0};
    // apexes above and below the edge; some right at 90 degrees (on the unit circle), some
    // almost on the edge's line (angles near 180 degrees), some far (angles near 0)
    const int kind = i % 4;
    auto apex = [&](double side) {
      const double t = uniform(0.05, 3.1);
      if (kind == 0) return std::array<double, 3>{std::cos(t), side * std::sin(t), uniform(-0.3, 0.3) * std::sin(t)};
      if (kind == 1) return std::array<double, 3>{uniform(-0.99, 0.99), side * uniform(1e-4, 1e-2), 0.0};
      if (kind == 2) return std::array<double, 3>{uniform(-2, 2), side * uniform(2, 20), uniform(-1, 1)};
      return std::array<double, 3>{uniform(-1.5, 1.5), side * uniform(0.01, 2), uniform(-2, 2)};
    };
    const std::array<double, 3> c = apex(1), d = apex(-1);
    const double sum = angleAt(c, a, b) + angleAt(d, b, a);
    if (std::abs(sum - 3.14159265358979323846) < 1e-9) continue;
    MeshBuffers m;
    for (const auto* p : {&a, &b, &c, &d}) m.positions.insert(m.positions.end(), p->begin(), p->end());
    m.triangles = {0, 1, 2, 1, 0, 3};
    const bool expected = sum <= 3.14159265358979323846;
    (expected ? delaunay : not_) += 1;
    INFO("pair " << i << ": opposite angles sum to " << sum);
    CHECK(edgeStats(m).delaunayFraction == (expected ? 1.0 : 0.0));
    CHECK(edgeStatsAndTopology(m).edges.delaunayFraction == (expected ? 1.0 : 0.0));
  }
  // both outcomes occur often enough for the test to mean something
  CHECK(delaunay > 500);
  CHECK(not_ > 500);
}

namespace {

//! max over the samples of `from` of the distance to the closest triangle of `to`, every triangle
//! tried (no tree).
double bruteForceOneSided(const MeshBuffers& from, const MeshBuffers& to, size_t samples, uint64_t seed) {
  const TriangleMeshDistance d(to);
  double worst = 0;
  for (const Vec3& p : surfaceSamples(from, samples, seed)) {
    double best = std::numeric_limits<double>::infinity();
    for (uint32_t f = 0; f < to.triangleCount(); ++f) best = std::min(best, d.faceDistanceSquared(f, p));
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

double wave(double x, double y) { return 0.25 * std::sin(4 * x) * std::cos(3 * y); }

//! The piecewise-linear surface of grid(n, wave) at (x, y): a finer grid whose vertices are
//! all on the coarse one (as the remesher's output vertices are on its input).
double onCoarse(int n, double x, double y) {
  int i = std::min(n - 1, int(x * n)), j = std::min(n - 1, int(y * n));
  double u = x * n - i, v = y * n - j;
  auto z = [n](int a, int b) { return wave(double(a) / n, double(b) / n); };
  if (u >= v) return z(i, j) + u * (z(i + 1, j) - z(i, j)) + v * (z(i + 1, j + 1) - z(i + 1, j));
  return z(i, j) + v * (z(i, j + 1) - z(i, j)) + u * (z(i + 1, j + 1) - z(i, j + 1));
}

}  // namespace

TEST_CASE("Hausdorff: each side is the brute-force max over its samples, with and without the means") {
  const MeshBuffers coarse = grid(7, wave);
  const MeshBuffers onInput = grid(29, [](double x, double y) { return onCoarse(7, x, y); });
  const MeshBuffers smooth = grid(23, wave);
  const MeshBuffers lifted = grid(11, [](double x, double y) { return wave(x, y) + 0.01 * x * y; });
  struct Pair {
    const MeshBuffers *a, *b;
  };
  for (Pair pr : {Pair{&onInput, &coarse}, Pair{&smooth, &coarse}, Pair{&coarse, &smooth}, Pair{&lifted, &smooth}}) {
    HausdorffOptions opt;
    opt.samplesPerSide = 3000;
    opt.seed = 5;
    const double aToB = bruteForceOneSided(*pr.a, *pr.b, opt.samplesPerSide, opt.seed);
    const double bToA = bruteForceOneSided(*pr.b, *pr.a, opt.samplesPerSide, opt.seed + 1);
    const HausdorffResult fast = hausdorffDistance(*pr.a, *pr.b, opt);
    // hints for A's vertices change the speed only, even arbitrary ones (some out of range: none)
    std::vector<uint32_t> hints(pr.a->vertexCount());
    for (size_t v = 0; v < hints.size(); ++v) hints[v] = uint32_t((v * 7) % (pr.b->triangleCount() + 3));
    opt.nearTriangleOfVertexA = &hints;
    const HausdorffResult hinted = hausdorffDistance(*pr.a, *pr.b, opt);
    opt.nearTriangleOfVertexA = nullptr;
    CHECK(hinted.aToB == aToB);
    CHECK(hinted.bToA == bToA);
    opt.computeMean = true;
    const HausdorffResult full = hausdorffDistance(*pr.a, *pr.b, opt);
    CHECK(aToB > 0);
    CHECK(fast.aToB == aToB);
    CHECK(fast.bToA == bToA);
    CHECK(full.aToB == aToB);
    CHECK(full.bToA == bToA);
    CHECK(fast.hausdorff == std::max(aToB, bToA));
    CHECK(fast.meanAToB == -1);
    CHECK(full.meanAToB > 0);
    CHECK(full.meanAToB <= full.aToB);
    CHECK(fast.samplesA == full.samplesA);
  }
}

TEST_CASE("Hausdorff: vertices on the reference measure 0; the samples between them measure the chords") {
  const MeshBuffers coarse = grid(7, wave);
  const MeshBuffers onInput = grid(29, [](double x, double y) { return onCoarse(7, x, y); });
  HausdorffOptions opt;
  opt.samplesPerSide = 0;  // vertices only
  HausdorffResult v = hausdorffDistance(onInput, coarse, opt);
  CHECK(v.aToB < 1e-15);
  CHECK(v.bToA > 1e-4);  // coarse vertices between the fine grid's lines are off its surface
  CHECK(v.bToA == bruteForceOneSided(coarse, onInput, 0, opt.seed + 1));
  // nothing to measure against: 0, as before (no triangle, or only ones with indices out of range)
  MeshBuffers none = coarse;
  none.triangles = {0, 1, 9999};
  CHECK(hausdorffDistance(coarse, none, HausdorffOptions{}).aToB == 0);
  none.triangles.clear();
  CHECK(hausdorffDistance(coarse, none, HausdorffOptions{}).aToB == 0);
  // surfaceSamples: the vertices first, then the area samples, deterministic
  const std::vector<Vec3> s1 = surfaceSamples(coarse, 500, 3), s2 = surfaceSamples(coarse, 500, 3);
  CHECK(s1.size() >= 64 + 500 - 98);  // 64 vertices; each of 98 triangles rounds its count up or down
  CHECK(s1 == s2);
  CHECK(s1[9] == Vec3{1.0 / 7, 1.0 / 7, wave(1.0 / 7, 1.0 / 7)});  // vertex (1, 1) of the 8×8
}
