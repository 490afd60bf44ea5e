#include <doctest/doctest.h>
#include "core/constants.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <string>

#include "features/creases.h"
#include "features/curve_mesh.h"
#include "features/edge_graph.h"
#include "features/segmentation.h"
#include "features/close_junctions.h"
#include "features/cut_junctions.h"
#include "features/merge_cut_patches.h"
#include "features/sizing.h"
#include "features/test_shapes.h"
#include "features/data_models.h"
#include "features/wedges.h"
#include "mesh/mesh_io.h"

using namespace conformesh;
using namespace conformesh::features;

namespace {
uint32_t countCorners(const Segmentation& s, uint8_t kind) {
  return uint32_t(std::count(s.vertexCorner.begin(), s.vertexCorner.end(), kind));
}
void checkPatchesAreDisks(const EdgeGraph& g, const Segmentation& s) {
  auto mask = s.curveMask();
  size_t faces = 0;
  for (size_t p = 0; p < s.patches.size(); ++p) {
    PatchMesh pm = extractPatch(g, mask, s.patches[p]);
    CHECK(pm.isDisk());
    for (uint32_t f : s.patches[p]) CHECK(s.facePatch[f] == p);
    faces += s.patches[p].size();
  }
  CHECK(faces == g.faceCount);
}
// The 4 x 4 grid of [0, 2] x [0, 1] (faces with angles of 26.6, 63.4 and 90 degrees).
MeshBuffers stretchedSquare() {
  MeshBuffers m = testshapes::square(4);
  for (size_t v = 0; v < m.vertexCount(); ++v) m.positions[3 * v] *= 2;
  return m;
}
// The vertex of g at (x, y, 0), or kNone.
uint32_t vertexAt(const EdgeGraph& g, double x, double y) {
  for (uint32_t v = 0; v < g.vertexCount; ++v)
    if (std::abs(g.positions[v].x - x) < 1e-12 && std::abs(g.positions[v].y - y) < 1e-12) return v;
  return kNone;
}
}  // namespace

TEST_CASE("features: cube has 12 feature curves, 8 corners, 6 disk patches") {
  EdgeGraph g = buildEdgeGraph(testshapes::cube(4));
  Segmentation s = segment(g, FeatureOptions{});
  CHECK(s.curves.size() == 12);
  CHECK(countCorners(s, 1) == 8);
  CHECK(countCorners(s, 2) == 0);
  CHECK(s.patches.size() == 6);
  CHECK(s.cutEdgeCount == 0);
  for (const auto& c : s.curves) {
    CHECK(c.kind == EdgeKind::Feature);
    CHECK(c.patches[0] != c.patches[1]);
    CHECK(c.length == doctest::Approx(1.0));
  }
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: a feature angle above 90 degrees finds no feature on the cube, which is cut into disks") {
  EdgeGraph g = buildEdgeGraph(testshapes::cube(6));
  FeatureOptions o;
  o.featureAngleDeg = 95;
  Segmentation s = segment(g, o);
  CHECK(s.sharpEdgeCount == 0);
  CHECK(s.patches.size() >= 2);
  CHECK(s.cutEdgeCount > 0);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: cylinder with caps: two circles with artificial corners, disks after cutting") {
  EdgeGraph g = buildEdgeGraph(testshapes::cylinder(24, 8, 4));
  Segmentation s = segment(g, FeatureOptions{});
  uint32_t features = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) features += s.edgeKind[e] == EdgeKind::Feature;
  CHECK(features == 48);
  CHECK(countCorners(s, 2) + countCorners(s, 1) >= 4);
  checkPatchesAreDisks(g, s);
  // Euler: V − E + F of the curve graph + patches = 2 for a sphere
  std::set<uint32_t> curveVerts;
  for (const auto& c : s.curves) curveVerts.insert(c.vertices.front()), curveVerts.insert(c.vertices.back());
  CHECK(long(curveVerts.size()) - long(s.curves.size()) + long(s.patches.size()) == 2);
}

TEST_CASE("features: torus (genus 1, closed) is cut into disks") {
  EdgeGraph g = buildEdgeGraph(testshapes::torus(32, 12));
  Segmentation s = segment(g, FeatureOptions{});
  CHECK(s.sharpEdgeCount == 0);
  CHECK(s.patches.size() >= 2);
  checkPatchesAreDisks(g, s);
  std::set<uint32_t> curveVerts;
  for (const auto& c : s.curves) curveVerts.insert(c.vertices.front()), curveVerts.insert(c.vertices.back());
  CHECK(long(curveVerts.size()) - long(s.curves.size()) + long(s.patches.size()) == 0);
}

TEST_CASE("features: bad options and bad user feature edges are errors") {
  EdgeGraph g = buildEdgeGraph(testshapes::square(3));
  FeatureOptions o;
  o.featureAngleDeg = -1;
  CHECK_THROWS_AS(segment(g, o), Error);
  o = {};
  o.featureEdges.push_back({0, 15});
  try {
    segment(g, o);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.code() == Code::InvalidArgument);
  }
}

TEST_CASE("features: curve samples lie on the input polyline, ends at corners, spacing follows the size") {
  EdgeGraph g = buildEdgeGraph(testshapes::cylinder(48, 8, 4));
  Segmentation s = segment(g, FeatureOptions{});
  SizingOptions so;
  so.targetEdgeLengthRel = 0.02;
  SizingField sz = computeSizing(g, s, so);
  CurveMesh cm = sampleCurves(g, s, sz);
  REQUIRE(cm.curveSamples.size() == s.curves.size());
  for (size_t c = 0; c < s.curves.size(); ++c) {
    const auto& ids = cm.curveSamples[c];
    REQUIRE(ids.size() >= 2);
    CHECK(cm.samples[ids.front()].vertex == s.curves[c].vertices.front());
    CHECK(cm.samples[ids.back()].vertex == s.curves[c].vertices.back());
    std::set<uint32_t> curveEdges(s.curves[c].edges.begin(), s.curves[c].edges.end());
    for (uint32_t id : ids) {
      const CurveSample& smp = cm.samples[id];
      if (smp.vertex != kNone)
        CHECK(std::count(s.curves[c].vertices.begin(), s.curves[c].vertices.end(), smp.vertex) >= 1);
      else
        CHECK(curveEdges.count(smp.edge) == 1);
      const Vec3& p0 = g.positions[g.edgeVerts[smp.edge][0]];
      const Vec3& p1 = g.positions[g.edgeVerts[smp.edge][1]];
      Vec3 q = p0 * (1 - smp.t) + p1 * smp.t;
      CHECK(norm(q - smp.position) <= 1e-12);
      CHECK(smp.t >= 0.0);
      CHECK(smp.t <= 1.0);
    }
    // chord lengths within a factor of the sizing (curvature makes them smaller, never larger)
    for (size_t i = 0; i + 1 < ids.size(); ++i) {
      double d = norm(cm.samples[ids[i + 1]].position - cm.samples[ids[i]].position);
      CHECK(d <= 1.6 * sz.maxLength);
      CHECK(d > 0.0);
    }
  }
}

TEST_CASE("sizing: graded, clamped, smaller where curved") {
  EdgeGraph g = buildEdgeGraph(testshapes::torus(64, 24, 1.0, 0.1));
  Segmentation s = segment(g, FeatureOptions{});
  SizingOptions so;
  so.targetEdgeLengthRel = 0.05;
  so.chordToleranceRel = 1e-4;
  SizingField sz = computeSizing(g, s, so);
  double lo = *std::min_element(sz.h.begin(), sz.h.end()), hi = *std::max_element(sz.h.begin(), sz.h.end());
  CHECK(lo >= sz.minLength);
  CHECK(hi <= sz.maxLength);
  CHECK(lo < sz.target);  // tube radius 0.1 with a tight chord tolerance
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    uint32_t a = g.edgeVerts[e][0], b = g.edgeVerts[e][1];
    CHECK(std::abs(sz.h[a] - sz.h[b]) <= 0.5 * g.edgeLength(e) * (1 + 1e-9));
  }
}

TEST_CASE("sizing: a cut vertex takes the surface's curvature, like its uncut neighbours on the same ring") {
  // the torus is the same all around its axis, so every vertex at one angle around the tube has
  // the same size, whether or not one of the cuts (a meridian and a longitude) passes through it;
  // a cut vertex used to take its cut's turn instead (1/(R + r cos v) along a longitude, not the
  // tube's 1/r), and the longitude's vertices got larger sizes than their ring
  const double R = 1.0, r = 0.1;
  EdgeGraph g = buildEdgeGraph(testshapes::torus(64, 24, R, r));
  Segmentation s = segment(g, FeatureOptions{});
  size_t cutEdges = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) cutEdges += s.edgeKind[e] == EdgeKind::Cut;
  REQUIRE(cutEdges > 0);
  SizingOptions so;
  so.targetEdgeLengthRel = 0.05;
  so.chordToleranceRel = 1e-4;
  SizingField sz = computeSizing(g, s, so);
  std::map<long, std::pair<double, double>> ring;  // tube angle (rounded) -> min, max size
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    const auto& p = g.positions[v];
    const long key = std::lround(std::atan2(p.z, std::hypot(p.x, p.y) - R) * 1e6);
    auto it = ring.emplace(key, std::make_pair(sz.h[v], sz.h[v])).first;
    it->second.first = std::min(it->second.first, sz.h[v]);
    it->second.second = std::max(it->second.second, sz.h[v]);
  }
  CHECK(ring.size() == 24);
  for (const auto& [key, mm] : ring) CHECK(mm.second <= mm.first * (1 + 1e-9));
}

TEST_CASE("sizing: a bend the output spans (a sharp edge that is no feature) bounds the size by the chord tolerance; a feature curve does not") {
  // a sheet folded by 60° along x = 0.5
  MeshBuffers m = testshapes::square(8);
  for (size_t v = 0; v < m.vertexCount(); ++v)
    if (m.positions[3 * v] > 0.5) m.positions[3 * v + 2] = (m.positions[3 * v] - 0.5) * std::tan(kPi / 3);
  EdgeGraph g = buildEdgeGraph(m);
  SizingOptions so;
  so.targetEdgeLengthRel = 0.1;
  so.chordToleranceRel = 1e-3;
  FeatureOptions smooth;
  smooth.featureAngleDeg = 90;  // the fold is no feature
  const Segmentation noFold = segment(g, smooth), fold = segment(g, FeatureOptions{});
  const SizingField across = computeSizing(g, noFold, so), along = computeSizing(g, fold, so);
  const double tol = 1e-3 * across.diagonal, bound = 2 * tol / std::sin(kPi / 6);
  size_t onFold = 0;
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    if (std::abs(g.positions[v].x - 0.5) > 1e-12) continue;
    ++onFold;
    CHECK(across.h[v] <= std::max(bound, across.minLength) * (1 + 1e-12));
    CHECK(along.h[v] > across.h[v]);  // the output follows the feature curve: no triangle spans it
  }
  CHECK(onFold == 9);
}

TEST_CASE("features: featureWedgeAngles gives the wedges between the input's own feature curves") {
  // cube(2): a corner has three 90° wedges, an edge midpoint two 180° ones, a face centre none
  EdgeGraph g = buildEdgeGraph(testshapes::cube(2));
  Segmentation s = segment(g, FeatureOptions{});
  std::vector<double> w = featureWedgeAngles(g, s);
  int corners = 0, edges = 0, centres = 0;  // vertices on 3, 2 and 1 faces of the cube
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    int onFace = 0;  // coordinates at 0 or 1 (the cube spans [0, s] or [-s/2, s/2]: count extremes)
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& q : g.positions) lo = std::min(lo, q.x), hi = std::max(hi, q.x);
    for (double c : {g.positions[v].x, g.positions[v].y, g.positions[v].z}) onFace += (std::abs(c - lo) < 1e-12 || std::abs(c - hi) < 1e-12);
    const double expect = onFace == 3 ? kPi / 2 : onFace == 2 ? kPi : 2 * kPi;
    CHECK(w[v] == doctest::Approx(expect));
    corners += onFace == 3;
    edges += onFace == 2;
    centres += onFace == 1;
  }
  CHECK(corners == 8);
  CHECK(edges == 12);
  CHECK(centres == 6);
}

namespace {
// Per cut end at a junction (three or more curve edges): the smallest angle, at the scale `l`,
// between the cut and the other curves there.
std::vector<double> cutJunctionAngles(const EdgeGraph& g, const Segmentation& s, double l) {
  auto along = [&](std::vector<uint32_t> path) {
    double acc = 0;
    for (size_t i = 1; i < path.size(); ++i) {
      Vec3 a = g.positions[path[i - 1]], b = g.positions[path[i]];
      double e = norm(b - a);
      if (acc + e >= l) return a + (b - a) * ((l - acc) / e);
      acc += e;
    }
    return g.positions[path.back()];
  };
  std::vector<uint32_t> valence(g.vertexCount, 0);
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (s.isCurveEdge(e)) ++valence[g.edgeVerts[e][0]], ++valence[g.edgeVerts[e][1]];
  std::vector<double> out;
  for (uint32_t ci = 0; ci < s.curves.size(); ++ci) {
    if (s.curves[ci].kind != EdgeKind::Cut) continue;
    for (int end = 0; end < 2; ++end) {
      std::vector<uint32_t> p = s.curves[ci].vertices;
      if (end) std::reverse(p.begin(), p.end());
      if (valence[p[0]] < 3) continue;
      const Vec3 d = along(p) - g.positions[p[0]];
      double best = kPi;
      for (uint32_t cj = 0; cj < s.curves.size(); ++cj) {
        if (cj == ci) continue;
        for (int e2 = 0; e2 < 2; ++e2) {
          std::vector<uint32_t> q = s.curves[cj].vertices;
          if (e2) std::reverse(q.begin(), q.end());
          if (q[0] == p[0]) best = std::min(best, angleBetween(d, along(q) - g.positions[p[0]]));
        }
      }
      out.push_back(best);
    }
  }
  return out;
}
}  // namespace

TEST_CASE("features: improveCutJunctions opens up cuts that meet other curves at small angles, patches stay disks") {
  // a torus cut into disks (Voronoi borders: oblique junctions and triple points)
  EdgeGraph g = buildEdgeGraph(testshapes::torus(96, 40));
  const double scale = 0.08;
  FeatureOptions plain;
  Segmentation s0 = segment(g, plain);
  FeatureOptions fo;
  fo.junctionScale = scale;
  Segmentation s1 = segment(g, fo);
  checkPatchesAreDisks(g, s1);
  auto below = [&](const Segmentation& s, double deg) {
    std::vector<double> a = cutJunctionAngles(g, s, scale);
    return std::count_if(a.begin(), a.end(), [&](double x) { return x < deg * kPi / 180; });
  };
  MESSAGE("cut ends meeting a curve below 45 deg: " << below(s0, 45) << " -> " << below(s1, 45) << " (" << s1.reroutedCutEnds << " rerouted)");
  CHECK(below(s1, 45) <= below(s0, 45));
  CHECK(below(s1, 30) <= below(s0, 30));
  CHECK(s1.reroutedCutEnds > 0);
}

TEST_CASE("features: improveCutJunctions reroutes a cut whose last input edge leaves the curve at a few degrees (a sliver face)") {
  // [0, 1]² as a grid of n × n squares (diagonals of slope 1), a feature along y = 1/2, and a
  // vertex S inserted in the face above the feature at V = (1/2, 1/2): the edge V - S leaves the
  // feature at 4.8°. The cut comes down x = 1/2 + h from the top side to (1/2 + h, 1/2 + h), then
  // to S and V: at the junction scale it meets the feature at about 70°, through its last edge at
  // 4.8° (the patch beside it has that corner, which no mesh can fix).
  const int n = 20;
  const double h = 1.0 / n;
  MeshBuffers m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.insert(m.positions.end(), {i * h, j * h, 0.0});
  const auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  const uint32_t S = uint32_t(m.positions.size() / 3);
  m.positions.insert(m.positions.end(), {0.5 + 0.6 * h, 0.5 + 0.05 * h, 0.0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (i == n / 2 && j == n / 2)
        m.triangles.insert(m.triangles.end(), {a, b, S, b, c, S, c, a, S});
      else
        m.triangles.insert(m.triangles.end(), {a, b, c});
      m.triangles.insert(m.triangles.end(), {a, c, d});
    }
  const EdgeGraph g = buildEdgeGraph(m);
  const uint32_t V = id(n / 2, n / 2);
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  const auto mark = [&](uint32_t a, uint32_t b, EdgeKind kind) {
    const uint32_t e = g.findEdge(a, b);
    REQUIRE(e != kNone);
    s.edgeKind[e] = kind;
  };
  for (int i = 0; i < n; ++i) mark(id(i, n / 2), id(i + 1, n / 2), EdgeKind::Feature);
  for (int j = n / 2 + 1; j < n; ++j) mark(id(n / 2 + 1, j), id(n / 2 + 1, j + 1), EdgeKind::Cut);
  mark(id(n / 2 + 1, n / 2 + 1), S, EdgeKind::Cut);
  mark(S, V, EdgeKind::Cut);
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 3);
  checkPatchesAreDisks(g, s);
  // the smallest angle between a cut edge and a feature edge at a vertex they share
  const auto narrowest = [&](const Segmentation& t) {
    double least = kPi;
    for (uint32_t v = 0; v < g.vertexCount; ++v)
      for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
        for (uint32_t q = g.vertexEdgeStart[v]; q < g.vertexEdgeStart[v + 1]; ++q) {
          const uint32_t a = g.vertexEdgeIds[k], b = g.vertexEdgeIds[q];
          if (t.edgeKind[a] != EdgeKind::Cut || t.edgeKind[b] != EdgeKind::Feature) continue;
          least = std::min(least, angleBetween(g.positions[g.otherVertex(a, v)] - g.positions[v], g.positions[g.otherVertex(b, v)] - g.positions[v]));
        }
    return least;
  };
  REQUIRE(narrowest(s) < 5 * kPi / 180);
  const std::vector<EdgeKind> before = s.edgeKind;
  CHECK(improveCutJunctions(g, s, 4 * h) >= 1);
  MESSAGE("narrowest cut-feature angle after: " << narrowest(s) * 180 / kPi << " deg");
  CHECK(narrowest(s) >= kNarrowCutWedge);
  CHECK(s.edgeKind[g.findEdge(S, V)] == EdgeKind::None);
  for (uint32_t e = 0; e < g.edgeCount(); ++e)  // the feature and the boundary stay as they were
    if (before[e] == EdgeKind::Feature || before[e] == EdgeKind::Boundary) CHECK(s.edgeKind[e] == before[e]);
  CHECK(s.patches.size() == 3);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: minFeatureLength keeps a network of short strong creases and user feature edges") {
  EdgeGraph g = buildEdgeGraph(testshapes::cube(4));  // 12 creases of length 1, flat around
  FeatureOptions keep;
  keep.minFeatureLength = 1.5;  // every crease is shorter: they hold each other up
  Segmentation s = segment(g, keep);
  CHECK(s.sharpEdgeCount == 48);
  CHECK(s.droppedFeatureEdges == 0);
  CHECK(s.curves.size() == 12);
  checkPatchesAreDisks(g, s);
}

namespace {
// An open bent sheet: panel A (z = 0, x in [0, 1]), a 45° chamfer strip S of width `w`, panel B
// (vertical, 1 high), extruded along y in [0, 1] with `n` rows; folds of 45° between them.
MeshBuffers chamferedSheet(double w, int n) {
  const double c = w / std::sqrt(2.0);
  const std::vector<std::array<double, 2>> profile = {{0, 0}, {0.5, 0}, {1, 0}, {1 + c, c}, {1 + c, c + 0.5}, {1 + c, c + 1}};
  MeshBuffers m;
  for (int j = 0; j <= n; ++j)
    for (const auto& p : profile) m.positions.insert(m.positions.end(), {p[0], double(j) / n, p[1]});
  const uint32_t k = uint32_t(profile.size());
  for (uint32_t j = 0; j < uint32_t(n); ++j)
    for (uint32_t i = 0; i + 1 < k; ++i) {
      const uint32_t a = j * k + i, b = a + 1, d = a + k, e = d + 1;
      m.triangles.insert(m.triangles.end(), {a, b, e, a, e, d});
    }
  return m;
}
}  // namespace

TEST_CASE("features: minPatchWidth merges a strip narrower than it into a neighbour, keeping its other border; never across user feature edges") {
  const double w = 0.01;
  EdgeGraph g = buildEdgeGraph(chamferedSheet(w, 8));
  Segmentation all = segment(g, FeatureOptions{});
  CHECK(all.patches.size() == 3);
  CHECK(all.sharpEdgeCount == 16);  // two fold lines of 8 edges
  CHECK(all.mergedNarrowPatches == 0);
  FeatureOptions wide;
  wide.minPatchWidth = 0.5 * w;  // the strip is wider: kept
  CHECK(segment(g, wide).patches.size() == 3);
  FeatureOptions narrow;
  narrow.minPatchWidth = 2 * w;
  Segmentation s = segment(g, narrow);
  CHECK(s.mergedNarrowPatches == 1);
  CHECK(s.patches.size() == 2);
  CHECK(s.droppedFeatureEdges == 8);
  CHECK(s.sharpEdgeCount == 8);  // one fold line stays and draws the chamfer
  size_t featureCurves = 0;
  for (const auto& c : s.curves) featureCurves += c.kind == EdgeKind::Feature;
  CHECK(featureCurves >= 1);
  checkPatchesAreDisks(g, s);
  // the panels are not narrow, whatever the strip does
  for (const auto& p : s.patches) CHECK(p.size() >= 16);
  // user feature edges on both fold lines: nothing to drop, the strip stays
  FeatureOptions user = narrow;
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (all.edgeKind[e] == EdgeKind::Feature) user.featureEdges.push_back({g.edgeVerts[e][0], g.edgeVerts[e][1]});
  Segmentation u = segment(g, user);
  CHECK(u.mergedNarrowPatches == 0);
  CHECK(u.patches.size() == 3);
  FeatureOptions bad;
  bad.minPatchWidth = -1;
  CHECK_THROWS(segment(g, bad));
}

TEST_CASE("features: straightenCutEars moves a cut across a one-face wedge below 45 degrees, patches stay disks") {
  // a 4 x 4 grid of [0, 2] x [0, 1] (faces with angles of 26.6, 63.4 and 90 degrees); a cut from
  // the left side to the bottom with a kink at (1.5, 0.5): left along y = 0.5, then back down a
  // diagonal, a wedge of one face of 26.6 degrees at the kink
  EdgeGraph g = buildEdgeGraph(stretchedSquare());
  auto at = [&](double x, double y) { return vertexAt(g, x, y); };
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  const std::vector<std::array<double, 2>> path = {{0, 0.5}, {0.5, 0.5}, {1, 0.5}, {1.5, 0.5}, {1, 0.25}, {1, 0}};
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const uint32_t e = g.findEdge(at(path[i][0], path[i][1]), at(path[i + 1][0], path[i + 1][1]));
    REQUIRE(e != kNone);
    s.edgeKind[e] = EdgeKind::Cut;
  }
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 2);
  Segmentation kinked = s;
  // a region: only wedges whose faces are in it are tried (the ear is the face at the kink)
  {
    const uint32_t kink = at(1.5, 0.5);
    std::vector<uint32_t> away, near;
    for (uint32_t f = 0; f < g.faceCount; ++f) {
      const bool atKink = g.faces[f][0] == kink || g.faces[f][1] == kink || g.faces[f][2] == kink;
      (atKink ? near : away).push_back(f);
    }
    Segmentation elsewhere = kinked;
    CHECK(straightenCutEars(g, elsewhere, away) == 0);
    CHECK(elsewhere.edgeKind == kinked.edgeKind);
    Segmentation there = kinked;
    CHECK(straightenCutEars(g, there, near) == 1);
    CHECK(there.edgeKind[g.findEdge(at(1, 0.5), at(1, 0.25))] == EdgeKind::Cut);
  }
  CHECK(straightenCutEars(g, s) == 1);
  CHECK(s.edgeKind[g.findEdge(at(1, 0.5), at(1.5, 0.5))] == EdgeKind::None);
  CHECK(s.edgeKind[g.findEdge(at(1.5, 0.5), at(1, 0.25))] == EdgeKind::None);
  CHECK(s.edgeKind[g.findEdge(at(1, 0.5), at(1, 0.25))] == EdgeKind::Cut);
  CHECK(s.patches.size() == 2);
  checkPatchesAreDisks(g, s);
  // nothing left to move: a second call changes nothing
  CHECK(straightenCutEars(g, s) == 0);
  // a right-angle turn is no ear
  Segmentation square = kinked;
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (square.edgeKind[e] == EdgeKind::Cut) square.edgeKind[e] = EdgeKind::None;
  for (const auto& [p, q] : std::vector<std::pair<std::array<double, 2>, std::array<double, 2>>>{
           {{0, 0.5}, {0.5, 0.5}}, {{0.5, 0.5}, {1, 0.5}}, {{1, 0.5}, {1, 0.25}}, {{1, 0.25}, {1, 0}}})
    square.edgeKind[g.findEdge(at(p[0], p[1]), at(q[0], q[1]))] = EdgeKind::Cut;
  rebuildCurves(g, square);
  CHECK(straightenCutEars(g, square) == 0);
}

TEST_CASE("features: extendDanglingCurves does not end a walk on another curve's dangling end beside its last edge") {
  // the grid of [0, 2] x [0, 1] flipped upside down (diagonals of slope -1/2; faces of 26.6,
  // 63.4 and 90 degrees). Two feature chains with a dangling end each: D = (0.5, 0.75), whose
  // straightest continuation is the diagonal to W = (1, 0.5), and W, the end of a chain from the
  // left side along y = 0.5. D is walked first (smaller index); the step D -> W would make a
  // wedge of 26.6 degrees at W between the walk and W's last edge, a corner no mesh can fix.
  MeshBuffers m = testshapes::square(4);
  for (size_t v = 0; v < m.vertexCount(); ++v) m.positions[3 * v] *= 2, m.positions[3 * v + 1] = 1 - m.positions[3 * v + 1];
  for (size_t t = 0; t < m.triangleCount(); ++t) std::swap(m.triangles[3 * t + 1], m.triangles[3 * t + 2]);
  EdgeGraph g = buildEdgeGraph(m);
  auto at = [&](double x, double y) { return vertexAt(g, x, y); };
  auto edge = [&](std::array<double, 2> p, std::array<double, 2> q) { return g.findEdge(at(p[0], p[1]), at(q[0], q[1])); };
  const uint32_t D = at(0.5, 0.75), W = at(1, 0.5);
  REQUIRE(D < W);
  REQUIRE(edge({0.5, 0.75}, {1, 0.5}) != kNone);  // the diagonal the walk from D would take
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  for (uint32_t e : {edge({0, 1}, {0.5, 0.75}), edge({0, 0.5}, {0.5, 0.5}), edge({0.5, 0.5}, {1, 0.5})}) {
    REQUIRE(e != kNone);
    s.edgeKind[e] = EdgeKind::Feature;
  }
  extendDanglingCurves(g, s);
  CHECK(s.edgeKind[edge({0.5, 0.75}, {1, 0.5})] == EdgeKind::None);
  // W continues straight on, D's walk took another way; no dangling end is left
  CHECK(s.edgeKind[edge({1, 0.5}, {1.5, 0.5})] == EdgeKind::Cut);
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    int valence = 0;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) valence += s.isCurveEdge(g.vertexEdgeIds[k]);
    CHECK_MESSAGE(valence != 1, "vertex ", v, " is a dangling end");
  }
  rebuildCurves(g, s);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: straightenCutEars moves a cut across a wedge whose rim is already a cut, and drops the branches left dangling") {
  // the grid of the test above; cuts: from the left side along y = 0.5 to (1, 0.5), round the
  // one face (1, 0.5), (1.5, 0.5), (1, 0.25), and from (1, 0.25) down to the bottom side. The
  // wedge of 26.6 degrees at (1.5, 0.5) has the cut (1, 0.5) - (1, 0.25) for its rim: moving the
  // cut across the face takes that edge off too, and both tails are left dangling: they go. No
  // cut is left (one patch, a disk), the smallest wedge at (1.5, 0.5) is gone.
  EdgeGraph g = buildEdgeGraph(stretchedSquare());
  auto at = [&](double x, double y) { return vertexAt(g, x, y); };
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  const std::vector<std::pair<std::array<double, 2>, std::array<double, 2>>> cuts = {
      {{0, 0.5}, {0.5, 0.5}}, {{0.5, 0.5}, {1, 0.5}}, {{1, 0.5}, {1.5, 0.5}}, {{1.5, 0.5}, {1, 0.25}},
      {{1, 0.25}, {1, 0.5}},  {{1, 0.25}, {1, 0}}};
  for (const auto& [p, q] : cuts) {
    const uint32_t e = g.findEdge(at(p[0], p[1]), at(q[0], q[1]));
    REQUIRE(e != kNone);
    s.edgeKind[e] = EdgeKind::Cut;
  }
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 3);
  CHECK(straightenCutEars(g, s) == 1);
  CHECK(std::count(s.edgeKind.begin(), s.edgeKind.end(), EdgeKind::Cut) == 0);
  CHECK(s.patches.size() == 1);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: straightenCutEars with keepSplit leaves a region in two patches at least, without it the same move joins them") {
  // the configuration of the test above on a finer grid (x spacing 0.125, y 0.0625): the cut
  // from the left side to (1, 0.5), round the face (1, 0.5), (1.125, 0.5), (1, 0.4375), and down
  // to the bottom side. Moving the cut across the face's 26.6° wedge prunes both tails, joining
  // the two regions they separate and the face into one patch.
  MeshBuffers m = testshapes::square(16);
  for (size_t v = 0; v < m.vertexCount(); ++v) m.positions[3 * v] *= 2;
  EdgeGraph g = buildEdgeGraph(m);
  auto at = [&](double x, double y) { return vertexAt(g, x, y); };
  Segmentation s = segment(g, FeatureOptions{});
  auto cut = [&](double x0, double y0, double x1, double y1) {
    const uint32_t e = g.findEdge(at(x0, y0), at(x1, y1));
    REQUIRE(e != kNone);
    s.edgeKind[e] = EdgeKind::Cut;
  };
  for (int i = 0; i < 8; ++i) cut(0.125 * i, 0.5, 0.125 * (i + 1), 0.5);
  cut(1, 0.5, 1.125, 0.5);
  cut(1.125, 0.5, 1, 0.4375);
  cut(1, 0.4375, 1, 0.5);
  for (int j = 0; j < 7; ++j) cut(1, 0.0625 * j, 1, 0.0625 * (j + 1));
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 3);
  std::vector<uint32_t> all(g.faceCount);
  for (uint32_t f = 0; f < g.faceCount; ++f) all[f] = f;
  Segmentation kept = s;
  CHECK(straightenCutEars(g, kept, all, true) == 0);
  CHECK(kept.patches.size() == 3);
  CHECK(straightenCutEars(g, s) == 1);
  CHECK(s.patches.size() == 1);
  checkPatchesAreDisks(g, s);
}

namespace {
// Vertices where exactly two curve edges meet, both cuts, at less than 45 degrees in 3D: a cut
// turning back on itself (a hairpin; no mesh gives the patch on its inner side good angles).
int cutHairpins(const EdgeGraph& g, const Segmentation& s) {
  int n = 0;
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    uint32_t cuts[2] = {kNone, kNone}, curves = 0, nc = 0;
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
      const uint32_t e = g.vertexEdgeIds[k];
      if (!s.isCurveEdge(e)) continue;
      ++curves;
      if (s.edgeKind[e] == EdgeKind::Cut && nc < 2) cuts[nc++] = e;
    }
    if (curves != 2 || nc != 2) continue;
    const Vec3 a = g.positions[g.otherVertex(cuts[0], v)] - g.positions[v];
    const Vec3 b = g.positions[g.otherVertex(cuts[1], v)] - g.positions[v];
    n += angleBetween(a, b) < 45.0 * kPi / 180.0;
  }
  return n;
}
}  // namespace

TEST_CASE("features: improveCutJunctions' reroutes add no cut hairpins (fertility, t13_data: shortest paths through needle fans did)") {
  for (const char* name : {"fertility.off", "t13_data.stl"}) {
    const EdgeGraph g = buildEdgeGraph(testshapes::dataModel(name));
    const Segmentation before = segment(g, FeatureOptions{});  // junctionScale 0: no reroutes
    Segmentation after = before;
    const uint32_t rerouted = improveCutJunctions(g, after, 0.01 * boundingBoxDiagonal(g));
    INFO(std::string(name) << ": " << rerouted << " cut ends rerouted, hairpins " << cutHairpins(g, before) << " -> " << cutHairpins(g, after));
    CHECK(rerouted > 0);
    CHECK(cutHairpins(g, after) <= cutHairpins(g, before));
    checkPatchesAreDisks(g, after);
  }
}

TEST_CASE("features: improveCutJunctions with a region reroutes only the cuts beside it (fertility)") {
  const EdgeGraph g = buildEdgeGraph(testshapes::dataModel("fertility.off"));
  const Segmentation s0 = segment(g, FeatureOptions{});  // junctionScale 0: no reroutes
  const double scale = 0.01 * boundingBoxDiagonal(g);
  // the region: the patch beside the first cut; cuts may move within it and the patches across
  // its cuts, nowhere else
  uint32_t region = kNone;
  for (const Curve& c : s0.curves)
    if (c.kind == EdgeKind::Cut && region == kNone) region = c.patches[0];
  REQUIRE(region != kNone);
  std::set<uint32_t> allowed{region};
  for (const Curve& c : s0.curves)
    if (c.kind == EdgeKind::Cut && (c.patches[0] == region || c.patches[1] == region)) allowed.insert({c.patches[0], c.patches[1]});
  Segmentation all = s0, local = s0;
  const uint32_t everywhere = improveCutJunctions(g, all, scale);
  const uint32_t here = improveCutJunctions(g, local, scale, s0.patches[region]);
  MESSAGE("rerouted: " << everywhere << " everywhere, " << here << " beside patch " << region << " of " << s0.patches.size());
  CHECK(everywhere > here);
  uint32_t changed = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    if (local.edgeKind[e] == s0.edgeKind[e]) continue;
    ++changed;
    for (uint32_t f : g.edgeFaces[e]) CHECK(allowed.count(s0.facePatch[f]) == 1);
  }
  CHECK((here == 0) == (changed == 0));
  checkPatchesAreDisks(g, local);
}

TEST_CASE("features: mergeCloseJunctions moves cut junctions off short curves; features stay, patches stay disks (camelhead, man)") {
  int modelsWithShortCurves = 0;
  for (const char* name : {"camelhead.off", "man.off"}) {
    const EdgeGraph g = buildEdgeGraph(testshapes::dataModel(name));
    FeatureOptions fo;
    fo.minFeatureLength = 0.02 * boundingBoxDiagonal(g);  // creases as the remesh finds them at 1 %
    const Segmentation before = segment(g, fo);            // junctionScale 0: no junction repairs
    const double minLength = 0.25 * 0.01 * boundingBoxDiagonal(g);
    // curves shorter than minLength with an end where only cuts meet besides it
    const auto shortAtCutJunction = [&](const Segmentation& s) {
      std::vector<uint32_t> nonCut(g.vertexCount, 0);
      for (const Curve& c : s.curves)
        if (c.kind != EdgeKind::Cut) ++nonCut[c.vertices.front()], ++nonCut[c.vertices.back()];
      uint32_t n = 0;
      for (const Curve& c : s.curves)
        if (c.length < minLength && c.vertices.front() != c.vertices.back())
          n += (nonCut[c.vertices.front()] == (c.kind != EdgeKind::Cut)) || (nonCut[c.vertices.back()] == (c.kind != EdgeKind::Cut));
      return n;
    };
    Segmentation after = before;
    const uint32_t merged = mergeCloseJunctions(g, after, minLength);
    INFO(std::string(name) << ": " << merged << " merged; short curves at cut junctions " << shortAtCutJunction(before) << " -> "
              << shortAtCutJunction(after));
    if (shortAtCutJunction(before) > 0) {
      ++modelsWithShortCurves;
      CHECK(merged > 0);
      CHECK(shortAtCutJunction(after) < shortAtCutJunction(before));
    }
    checkPatchesAreDisks(g, after);
    CHECK(after.patches.size() == before.patches.size());
    uint32_t featuresChanged = 0;  // only cuts move: features and boundaries stay as they are
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      featuresChanged += (before.edgeKind[e] == EdgeKind::Feature || before.edgeKind[e] == EdgeKind::Boundary ||
                          after.edgeKind[e] == EdgeKind::Feature || after.edgeKind[e] == EdgeKind::Boundary) &&
                         after.edgeKind[e] != before.edgeKind[e];
    CHECK(featuresChanged == 0);
  }
  CHECK(modelsWithShortCurves > 0);  // the test sees a merge at all
}

namespace {
// User feature edges along the closed polyline of grid points (i, j) of testshapes::square(n).
void gridLoop(const EdgeGraph& g, int n, const std::vector<std::array<int, 2>>& pts, FeatureOptions& o) {
  for (size_t k = 0; k < pts.size(); ++k) {
    const auto a = pts[k], b = pts[(k + 1) % pts.size()];
    o.featureEdges.push_back({vertexAt(g, double(a[0]) / n, double(a[1]) / n), vertexAt(g, double(b[0]) / n, double(b[1]) / n)});
  }
}
// The border of the grid rectangle [x0, x1] x [y0, y1], counterclockwise.
std::vector<std::array<int, 2>> gridRect(int x0, int y0, int x1, int y1) {
  std::vector<std::array<int, 2>> p;
  for (int x = x0; x < x1; ++x) p.push_back({x, y0});
  for (int y = y0; y < y1; ++y) p.push_back({x1, y});
  for (int x = x1; x > x0; --x) p.push_back({x, y1});
  for (int y = y1; y > y0; --y) p.push_back({x0, y});
  return p;
}
}  // namespace

TEST_CASE("features: a region with holes is halved across its loops, one patch per hole at most beyond the first two") {
  // a square with three closed feature loops inside: the region around them has four border
  // loops; each halving joins one loop to the others, so it needs at most four patches
  const int n = 24;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  FeatureOptions o;
  gridLoop(g, n, gridRect(4, 4, 6, 6), o);
  gridLoop(g, n, gridRect(16, 5, 18, 7), o);
  gridLoop(g, n, gridRect(10, 16, 12, 18), o);
  const Segmentation s = segment(g, o);
  CHECK(s.cutEdgeCount > 0);
  CHECK(s.patches.size() <= 3 + 4);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: a region touching itself at a vertex is cut in two there, a wedge in each part") {
  // a feature loop from a border vertex v into the square and back to v: the region outside it
  // has two wedges at v (a pinch); the two parts of the cut each keep one
  const int n = 12;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  FeatureOptions o;
  gridLoop(g, n, {{0, 6}, {1, 7}, {2, 7}, {3, 7}, {3, 6}, {3, 5}, {2, 5}, {1, 5}, {1, 6}}, o);
  const Segmentation s = segment(g, o);
  CHECK(s.patches.size() == 3);
  checkPatchesAreDisks(g, s);
  const uint32_t v = vertexAt(g, 0.0, 0.5);
  std::set<uint32_t> around;
  for (uint32_t f = 0; f < g.faceCount; ++f)
    for (int c = 0; c < 3; ++c)
      if (g.faces[f][c] == v) around.insert(s.facePatch[f]);
  CHECK(around.size() == 3);  // the loop's inside and the two parts of the outside
}

TEST_CASE("features: absorbCutSlivers joins a face cut all round to its neighbour when a corner is below the bound") {
  const int n = 6;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  // the face (2, 2), (3, 2), (3, 3) of the grid: corners of 45, 90 and 45 degrees
  const uint32_t a = vertexAt(g, 2.0 / n, 2.0 / n), b = vertexAt(g, 3.0 / n, 2.0 / n), c = vertexAt(g, 3.0 / n, 3.0 / n);
  for (auto [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const uint32_t e = g.findEdge(x, y);
    REQUIRE(e != kNone);
    s.edgeKind[e] = EdgeKind::Cut;
  }
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 2);
  const std::vector<EdgeKind> cut = s.edgeKind;
  CHECK(absorbCutSlivers(g, s, 40.0 * kPi / 180) == 0);  // 45 degrees: no sliver at this bound
  CHECK(s.edgeKind == cut);
  CHECK(absorbCutSlivers(g, s, 50.0 * kPi / 180) == 1);
  CHECK(s.patches.size() == 1);
  CHECK(s.cutEdgeCount == 0);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: moveNarrowCutWedges gives a wedge below the bound between two cuts to the patch across one") {
  // a square grid cut along y = 1/2 and along the diagonal from its centre v to the corner
  // (1, 1): the patch between the two right of v has a 45-degree corner at v
  const int n = 6;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  const uint32_t v = vertexAt(g, 0.5, 0.5);
  const auto cutPath = [&](const std::vector<std::pair<int, int>>& at) {
    for (size_t i = 0; i + 1 < at.size(); ++i) {
      const uint32_t e = g.findEdge(vertexAt(g, at[i].first / double(n), at[i].second / double(n)),
                                    vertexAt(g, at[i + 1].first / double(n), at[i + 1].second / double(n)));
      REQUIRE(e != kNone);
      s.edgeKind[e] = EdgeKind::Cut;
    }
  };
  cutPath({{0, 3}, {1, 3}, {2, 3}, {3, 3}, {4, 3}, {5, 3}, {6, 3}});
  cutPath({{3, 3}, {4, 4}, {5, 5}, {6, 6}});
  rebuildCurves(g, s);
  REQUIRE(s.patches.size() == 3);
  const auto smallest = [&](uint32_t x) {
    WedgeScratch w;
    return smallestWedge(g, x, [&](uint32_t e) { return s.isCurveEdge(e); }, w);
  };
  REQUIRE(smallest(v) == doctest::Approx(kPi / 4));
  const std::vector<EdgeKind> cut = s.edgeKind;
  CHECK(moveNarrowCutWedges(g, s, 40.0 * kPi / 180) == 0);  // 45 degrees: nothing to move at this bound
  CHECK(s.edgeKind == cut);
  const uint32_t wedgeFace = [&] {  // the face in the wedge at v
    for (uint32_t f = 0; f < g.faceCount; ++f)
      if (std::count(g.faces[f].begin(), g.faces[f].end(), v) && std::count(g.faces[f].begin(), g.faces[f].end(), vertexAt(g, 4.0 / n, 0.5)) &&
          std::count(g.faces[f].begin(), g.faces[f].end(), vertexAt(g, 4.0 / n, 4.0 / n)))
        return f;
    return kNone;
  }();
  REQUIRE(wedgeFace != kNone);
  const uint32_t topLeft = s.facePatch[std::find_if(s.patches.begin(), s.patches.end(), [&](const auto& faces) {
                                         return std::any_of(faces.begin(), faces.end(), [&](uint32_t f) { return g.faceCentroid(f).x < 0.3 && g.faceCentroid(f).y > 0.6; });
                                       })->front()];
  // v's wedge, and the diagonal's at the corner (1, 1), where it meets the border at 45 degrees
  CHECK(moveNarrowCutWedges(g, s, 50.0 * kPi / 180) == 2);
  CHECK(s.patches.size() == 3);
  CHECK(s.facePatch[wedgeFace] == topLeft);  // across the longer side, the diagonal
  CHECK(smallest(v) >= 50.0 * kPi / 180);
  for (uint32_t x = 0; x < g.vertexCount; ++x) CHECK(smallest(x) >= 45.0 * kPi / 180 - 1e-12);
  uint32_t cuts = 0;
  for (EdgeKind k : s.edgeKind) cuts += k == EdgeKind::Cut;
  CHECK(s.cutEdgeCount == cuts);
  checkPatchesAreDisks(g, s);
}

TEST_CASE("features: a curve's chord from a corner that would close a wedge below the bound gets a sample at its kink") {
  // a square grid, a feature from J = (1/2, 0) on the border diagonally to (7/12, 1/12), then
  // along y = 1/12 to the border: its first edge leaves the border at 45 degrees, but its chord
  // from J to its first sample (at about x = 0.77) at 17 degrees
  const int n = 12;
  const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
  std::vector<std::pair<int, int>> path{{6, 0}};
  for (int x = 7; x <= n; ++x) path.push_back({x, 1});
  FeatureOptions fo;
  for (size_t i = 0; i + 1 < path.size(); ++i)
    fo.featureEdges.push_back({vertexAt(g, path[i].first / double(n), path[i].second / double(n)),
                               vertexAt(g, path[i + 1].first / double(n), path[i + 1].second / double(n))});
  const uint32_t kink = vertexAt(g, 7.0 / n, 1.0 / n);
  SizingOptions so;
  so.targetEdgeLength = 2.0;  // as few segments per curve as the patches allow
  for (double bound : {30.0, 10.0}) {
    fo.angleBoundDeg = bound;
    const Segmentation s = segment(g, fo);
    const CurveMesh cm = sampleCurves(g, s, computeSizing(g, s, so));
    const uint32_t c = s.edgeCurve[g.findEdge(fo.featureEdges[0][0], fo.featureEdges[0][1])];
    REQUIRE(c != kNone);
    REQUIRE(s.curves[c].vertices.size() == path.size());
    bool sampled = false;
    for (uint32_t id : cm.curveSamples[c]) sampled = sampled || cm.samples[id].vertex == kink;
    INFO("bound " << bound);
    CHECK(sampled == (bound > 20));
  }
}

TEST_CASE("features: above a 30-degree bound the outlier tests look at the same faces (a face whose tips are all 30 degrees or more is no sliver)") {
  // triangle (a, b, c) of a flat grid split at p, beside the middle of ab and lifted: the face
  // (a, b, p) stands 75° out of the sheet with corners of about 32.5° at a and b, its three
  // edges sharp; the faces around it bend by much less
  MeshBuffers m = testshapes::square(8);
  const size_t t = 3 * 70;
  const uint32_t a = m.triangles[t], b = m.triangles[t + 1], c = m.triangles[t + 2];
  double mid[3], along[2], side[2];
  for (int k = 0; k < 3; ++k) mid[k] = 0.5 * (m.positions[3 * a + k] + m.positions[3 * b + k]);
  for (int k = 0; k < 2; ++k) along[k] = m.positions[3 * b + k] - m.positions[3 * a + k], side[k] = m.positions[3 * c + k] - mid[k];
  const double ab = std::hypot(along[0], along[1]);
  const double s0 = (side[0] * along[0] + side[1] * along[1]) / (ab * ab);
  double perp[2] = {side[0] - s0 * along[0], side[1] - s0 * along[1]};
  const double pn = std::hypot(perp[0], perp[1]);
  const double tilt = 75 * kPi / 180, rise = 0.5 * ab * std::tan(32.5 * kPi / 180);  // p's height over ab
  const double p[3] = {mid[0] + rise * std::cos(tilt) * perp[0] / pn, mid[1] + rise * std::cos(tilt) * perp[1] / pn, rise * std::sin(tilt)};
  const uint32_t pi = uint32_t(m.vertexCount());
  m.positions.insert(m.positions.end(), p, p + 3);
  m.triangles[t + 2] = pi;
  m.triangles.insert(m.triangles.end(), {b, c, pi, c, a, pi});
  const EdgeGraph g = buildEdgeGraph(m);
  const uint32_t face = uint32_t(t / 3);
  for (int k = 0; k < 3; ++k) {
    INFO("corner " << k);
    CHECK(g.cornerAngle(face, k) * 180 / kPi >= 30);
  }
  const Creases sharp = detectCreases(g, CreaseOptions{});  // every candidate
  REQUIRE((sharp.edge[g.findEdge(a, b)] && sharp.edge[g.findEdge(a, pi)] && sharp.edge[g.findEdge(b, pi)]));
  const auto features = [&](double bound) {
    FeatureOptions o;
    o.minFeatureLength = 0.01;
    o.angleBoundDeg = bound;
    const Segmentation s = segment(g, o);
    std::vector<uint32_t> out;
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (s.edgeKind[e] == EdgeKind::Feature) out.push_back(e);
    return out;
  };
  const std::vector<uint32_t> at30 = features(30);
  CHECK(std::count(at30.begin(), at30.end(), g.findEdge(a, b)) == 1);  // its edge on the sheet is a crease
  CHECK(features(35) == at30);
}

namespace {
// s as rebuildCurves left it is what a rebuild from scratch gives, ids and orders included.
void checkSameAsScratch(const EdgeGraph& g, const Segmentation& s) {
  Segmentation f = s;
  f.builtKind.clear();
  rebuildCurves(g, f);
  REQUIRE(s.curves.size() == f.curves.size());
  for (size_t c = 0; c < s.curves.size(); ++c) {
    const Curve &a = s.curves[c], &b = f.curves[c];
    CHECK((a.vertices == b.vertices && a.edges == b.edges && a.kind == b.kind && a.patches == b.patches &&
           a.length == b.length && a.order == b.order));
  }
  CHECK(s.edgeCurve == f.edgeCurve);
  CHECK(s.vertexCorner == f.vertexCorner);
  CHECK(s.facePatch == f.facePatch);
  CHECK(s.patches == f.patches);
}
}  // namespace

TEST_CASE("features: rebuildCurves after local changes gives what a rebuild from scratch gives, ids included (cylinder loops, man)") {
  for (const MeshBuffers& mesh : {testshapes::cylinder(24, 8, 4), testshapes::dataModel("man.off")}) {
    const EdgeGraph g = buildEdgeGraph(mesh);
    FeatureOptions fo;
    fo.minFeatureLength = 0.02 * boundingBoxDiagonal(g);
    fo.junctionScale = 0.01 * boundingBoxDiagonal(g);
    Segmentation s = segment(g, fo);
    REQUIRE(s.builtKind == s.edgeKind);  // built: the next rebuild is a local one
    checkSameAsScratch(g, s);
    for (EdgeKind& k : s.edgeKind)  // the cuts gone: the cylinder's circles close without a corner
      if (k == EdgeKind::Cut) k = EdgeKind::None;
    rebuildCurves(g, s);
    checkSameAsScratch(g, s);
    const size_t loops = size_t(std::count(s.vertexCorner.begin(), s.vertexCorner.end(), 2));
    std::mt19937 rng(7);
    for (int step = 0; step < 80; ++step) {
      // a walk of 1-6 edges from a random vertex, each edge given a random kind (boundaries stay)
      uint32_t v = uint32_t(rng() % g.vertexCount);
      const uint32_t length = 1 + uint32_t(rng() % 6);
      for (uint32_t i = 0; i < length; ++i) {
        const uint32_t k = g.vertexEdgeStart[v] + uint32_t(rng() % (g.vertexEdgeStart[v + 1] - g.vertexEdgeStart[v]));
        const uint32_t e = g.vertexEdgeIds[k];
        if (!g.isBoundary(e)) s.edgeKind[e] = std::array<EdgeKind, 3>{EdgeKind::None, EdgeKind::Feature, EdgeKind::Cut}[rng() % 3];
        v = g.otherVertex(e, v);
      }
      const Segmentation before = s;
      rebuildCurves(g, s);
      checkSameAsScratch(g, s);
      if (step % 10 == 9) {  // undone: back to the curves and patches before
        const std::vector<EdgeKind> kinds = s.edgeKind;
        s.edgeKind = before.builtKind;
        rebuildCurves(g, s);
        checkSameAsScratch(g, s);
        CHECK(s.patches == before.patches);
        s.edgeKind = kinds;
        rebuildCurves(g, s);
      }
    }
    // patch splits, as the flattening makes them
    for (int i = 0; i < 4; ++i) {
      uint32_t largest = 0;
      for (uint32_t p = 0; p < s.patches.size(); ++p)
        if (s.patches[p].size() > s.patches[largest].size()) largest = p;
      REQUIRE(splitPatch(g, s, largest));
      checkSameAsScratch(g, s);
    }
    if (mesh.vertexCount() < 1000) CHECK(loops > 0);  // the cylinder's circles are loops without a corner
  }
}

TEST_CASE("features: splitPatch with seed faces puts them in different parts, where farthest points keep neighbours together") {
  const EdgeGraph g = buildEdgeGraph(testshapes::square(8));
  Segmentation s = segment(g, FeatureOptions{});
  REQUIRE(s.patches.size() == 1);
  // two faces beside one inner edge near a corner of the square
  uint32_t a = kNone, b = kNone;
  for (uint32_t e = 0; e < g.edgeCount() && a == kNone; ++e)
    if (!g.isBoundary(e)) a = g.edgeFaces[e][0], b = g.edgeFaces[e][1];
  REQUIRE(a != kNone);
  Segmentation far = s, apart = s;
  REQUIRE(splitPatch(g, far, 0));
  CHECK(far.facePatch[a] == far.facePatch[b]);  // the farthest points lie at opposite corners
  REQUIRE(splitPatch(g, s, 0, 2, {a, b}));
  CHECK(s.facePatch[a] != s.facePatch[b]);
  checkPatchesAreDisks(g, s);
  // seeds the farthest points already part: their split as it is
  uint32_t c = kNone;
  for (uint32_t f = 0; f < g.faceCount && c == kNone; ++f)
    if (far.facePatch[f] != far.facePatch[a]) c = f;
  REQUIRE(c != kNone);
  REQUIRE(splitPatch(g, apart, 0, 2, {a, c}));
  CHECK(apart.edgeKind == far.edgeKind);
}

TEST_CASE("features: mergeCutPatches joins a strip narrower than the width across its cuts; a union that is no disk stays apart") {
  SUBCASE("a one-row strip of a square joins the region beside it; the wider regions stay") {
    const int n = 12;
    const EdgeGraph g = buildEdgeGraph(testshapes::square(n));
    Segmentation s = segment(g, FeatureOptions{});
    REQUIRE(s.patches.size() == 1);
    // cuts along the grid lines y = 1/n and y = 6/n: a strip 1/n wide, one 5/n wide, one 6/n wide
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      const Vec3 a = g.positions[g.edgeVerts[e][0]], b = g.positions[g.edgeVerts[e][1]];
      for (int row : {1, 6})
        if (std::abs(a.y - double(row) / n) < 1e-12 && std::abs(b.y - double(row) / n) < 1e-12 && !g.isBoundary(e)) {
          s.edgeKind[e] = EdgeKind::Cut;
          ++s.cutEdgeCount;
        }
    }
    rebuildCurves(g, s);
    REQUIRE(s.patches.size() == 3);
    const std::vector<EdgeKind> before = s.edgeKind;
    CHECK(mergeCutPatches(g, s, 2.0 / n) == 1);
    rebuildCurves(g, s);
    CHECK(s.patches.size() == 2);
    checkPatchesAreDisks(g, s);
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      const double y = g.positions[g.edgeVerts[e][0]].y;
      if (before[e] != EdgeKind::Cut) CHECK(s.edgeKind[e] == before[e]);  // nothing but cuts changes
      else CHECK(s.edgeKind[e] == (std::abs(y - 1.0 / n) < 1e-12 ? EdgeKind::None : EdgeKind::Cut));
    }
    Segmentation none = s;
    CHECK(mergeCutPatches(g, none, 0.0) == 0);  // no width, no join
  }
  SUBCASE("the disks of a closed cube and of a torus never join into a closed or a holed patch, whatever the width") {
    for (const MeshBuffers& m : {testshapes::cube(6), testshapes::torus(32, 12)}) {
      const EdgeGraph g = buildEdgeGraph(m);
      FeatureOptions o;
      o.featureAngleDeg = 100;  // no crease: the surface is cut into disks only
      Segmentation s = segment(g, o);
      REQUIRE(s.patches.size() >= 2);
      mergeCutPatches(g, s, 10 * boundingBoxDiagonal(g));
      rebuildCurves(g, s);
      CHECK(s.patches.size() >= 2);
      checkPatchesAreDisks(g, s);
    }
  }
  SUBCASE("man, as the remesh segments it at 1 %: fewer patches narrower than an output edge, all disks, the features as they were") {
    const EdgeGraph g = buildEdgeGraph(testshapes::dataModel("man.off"));
    const double target = 0.01 * boundingBoxDiagonal(g);
    FeatureOptions fo;
    fo.minFeatureLength = 2 * target;
    Segmentation s = segment(g, fo);  // junctionScale 0: no joins, no junction repairs
    const auto narrow = [&](const Segmentation& x) {
      size_t count = 0;
      for (const auto& faces : x.patches) {
        double area = 0, perimeter = 0;
        for (uint32_t f : faces) {
          area += g.faceArea(f);
          for (uint32_t e : g.faceEdges[f]) {
            const uint32_t o = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];
            if (o == kNone || x.facePatch[o] != x.facePatch[f]) perimeter += g.edgeLength(e);
          }
        }
        count += 2 * area < target * perimeter;
      }
      return count;
    };
    const Segmentation before = s;
    const uint32_t joins = mergeCutPatches(g, s, target);
    rebuildCurves(g, s);
    INFO("joins " << joins << ", patches " << before.patches.size() << " -> " << s.patches.size() << ", narrow " << narrow(before)
                  << " -> " << narrow(s));
    CHECK(joins > 0);
    CHECK(s.patches.size() == before.patches.size() - joins);
    CHECK(narrow(s) < narrow(before));
    checkPatchesAreDisks(g, s);
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (before.edgeKind[e] != EdgeKind::Cut) CHECK(s.edgeKind[e] == before.edgeKind[e]);
  }
  SUBCASE("man at 1 %, in pairs: each joined patch is two patches as they were, no kept cut made plain, the faces bounded") {
    const EdgeGraph g = buildEdgeGraph(testshapes::dataModel("man.off"));
    const double target = 0.01 * boundingBoxDiagonal(g);
    FeatureOptions fo;
    fo.minFeatureLength = 2 * target;
    const Segmentation before = segment(g, fo);
    // every other cut edge kept
    std::vector<uint8_t> keep(g.edgeCount(), 0);
    size_t cuts = 0;
    for (uint32_t e = 0; e < g.edgeCount(); ++e)
      if (before.edgeKind[e] == EdgeKind::Cut) keep[e] = cuts++ % 2;
    for (const size_t maxFaces : {size_t(g.faceCount / 8), size_t(g.faceCount)}) {
      CAPTURE(maxFaces);
      Segmentation s = before;
      const uint32_t joins = mergeCutPatches(g, s, 3 * target, {}, keep, true, maxFaces);
      rebuildCurves(g, s);
      CHECK(joins > 0);
      CHECK(s.patches.size() == before.patches.size() - joins);
      checkPatchesAreDisks(g, s);
      for (uint32_t e = 0; e < g.edgeCount(); ++e)
        if (keep[e] || before.edgeKind[e] != EdgeKind::Cut) CHECK(s.edgeKind[e] == before.edgeKind[e]);
      size_t joinedFaces = 0;
      for (const auto& faces : s.patches) {
        std::set<uint32_t> parts;
        for (uint32_t f : faces) parts.insert(before.facePatch[f]);
        CHECK(parts.size() <= 2);
        if (parts.size() == 2) joinedFaces += faces.size();
      }
      CHECK(joinedFaces <= maxFaces);
    }
  }
}

// The junction repairs after a split (improveCutJunctions reroutes cut ends, the others move ears,
// slivers and narrow wedges) must keep what the cuts parted: a repair that puts more than half of
// the smaller side back in the largest part is dropped, else the split is undone but for a
// sliver and the flattening splits the patch again (man: 346 faces split into 116 and 230 came
// out as 343 and 3). The cuts as made are the split with the repairs off (no junction scale, no
// angle bound to repair towards).
TEST_CASE("features: splitPatch's junction repairs keep at least half of what its cuts parted") {
  for (const char* name : {"man.off", "camel.off"}) {
    CAPTURE(name);
    const EdgeGraph g = buildEdgeGraph(testshapes::dataModel(name));
    const Segmentation s = segment(g, testshapes::remeshFeatureOptions(g));
    size_t splits = 0;
    for (uint32_t p = 0; p < s.patches.size(); ++p) {
      const std::vector<uint32_t> region = s.patches[p];
      if (region.size() < 16) continue;
      Segmentation repaired = s, raw = s;
      raw.junctionScale = 0;
      raw.angleBoundDeg = 0;
      if (!splitPatch(g, repaired, p) || !splitPatch(g, raw, p)) continue;
      ++splits;
      const size_t parted = region.size() - largestShare(raw, region);
      CAPTURE(p);
      CAPTURE(region.size());
      CHECK(parted > 0);
      CHECK(largestShare(repaired, region) <= region.size() - (parted + 1) / 2);
      checkPatchesAreDisks(g, repaired);
    }
    CHECK(splits >= 10);
  }
}

// A cone's tip is cut off by an output that spans it by its slope times the distance to the
// nearest output vertex: a linear error, which the curvature bound (a quadratic one) leaves
// several tolerances wide at a sharp tip. With coneTips the tip's size puts an output vertex
// within the tolerance of it; the flanks (slope the same, but on the rim's curve or graded from
// the tip) are not asked for more.
TEST_CASE("sizing: coneTips bounds the size at a cone's tip by its slope; off, the curvature alone") {
  const EdgeGraph g = buildEdgeGraph(testshapes::raisedDisk([](double r) { return 0.5 * (1 - r); }));
  const Segmentation s = segment(g, FeatureOptions{});
  const uint32_t tip = 0;  // raisedDisk's centre
  SizingOptions so;
  so.targetEdgeLengthRel = 0.05;
  so.chordToleranceRel = 1e-3;
  const SizingField plain = computeSizing(g, s, so);
  so.coneTips = true;
  const SizingField cone = computeSizing(g, s, so);
  const double tol = 1e-3 * cone.diagonal, slope = surfaceSlope(g)[tip];
  CHECK(slope == doctest::Approx(0.5 / std::sqrt(1.25)));
  CHECK(cone.h[tip] <= std::max(cone.minLength, std::sqrt(3.0) * tol / slope) * (1 + 1e-12));
  CHECK(plain.h[tip] > 1.5 * cone.h[tip]);
  for (uint32_t v = 0; v < g.vertexCount; ++v) CHECK(cone.h[v] <= plain.h[v] * (1 + 1e-12));
}

TEST_CASE("features: isDiskRegion agrees with extractPatch on patches, unions of neighbours, grown regions and pinches") {
  // regions of every kind: the remesh's patches of man and of a torus, each patch with each
  // neighbour (across their cuts made plain, or kept), random regions grown from a face with
  // random curve edges inside, and a region touching itself at one vertex
  size_t disks = 0, others = 0;
  const auto agree = [&](const EdgeGraph& g, const std::vector<uint8_t>& mask, const std::vector<uint32_t>& faces) {
    const bool disk = extractPatch(g, mask, faces, false).isDisk();
    CHECK(isDiskRegion(g, mask, faces) == disk);
    ++(disk ? disks : others);
  };
  std::mt19937 rng(7);
  for (const MeshBuffers& m : {testshapes::dataModel("man.off"), testshapes::torus(32, 12)}) {
    const EdgeGraph g = buildEdgeGraph(m);
    const Segmentation s = segment(g, testshapes::remeshFeatureOptions(g));
    std::vector<uint8_t> mask = s.curveMask();
    for (const auto& faces : s.patches) agree(g, mask, faces);
    for (uint32_t e = 0; e < g.edgeCount(); ++e) {
      const auto [f0, f1] = std::pair{g.edgeFaces[e][0], g.edgeFaces[e][1]};
      if (f1 == kNone || s.facePatch[f0] >= s.facePatch[f1] || e % 7) continue;  // a sample of the pairs
      std::vector<uint32_t> both = s.patches[s.facePatch[f0]];
      both.insert(both.end(), s.patches[s.facePatch[f1]].begin(), s.patches[s.facePatch[f1]].end());
      agree(g, mask, both);
      std::vector<uint8_t> plain = mask;
      for (uint32_t d = 0; d < g.edgeCount(); ++d)
        if (g.edgeFaces[d][1] != kNone && std::minmax(s.facePatch[g.edgeFaces[d][0]], s.facePatch[g.edgeFaces[d][1]]) == std::minmax(s.facePatch[f0], s.facePatch[f1]))
          plain[d] = 0;
      agree(g, plain, both);
    }
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<uint8_t> in(g.faceCount, 0), curve(g.edgeCount(), 0);
      for (uint32_t e = 0; e < g.edgeCount(); ++e) curve[e] = rng() % 50 == 0;
      std::vector<uint32_t> region{uint32_t(rng() % g.faceCount)};
      in[region[0]] = 1;
      const size_t size = 1 + rng() % 400;
      for (size_t k = 0; k < region.size() && region.size() < size; ++k)
        for (const uint32_t e : g.faceEdges[region[k]])
          for (const uint32_t f : g.edgeFaces[e])
            if (f != kNone && !in[f] && rng() % 4 != 0) in[f] = 1, region.push_back(f);
      agree(g, curve, region);
    }
  }
  {  // a torus but one face: one border loop and no pinch, but a handle
    const EdgeGraph g = buildEdgeGraph(testshapes::torus(16, 8));
    std::vector<uint32_t> most;
    for (uint32_t f = 1; f < g.faceCount; ++f) most.push_back(f);
    agree(g, std::vector<uint8_t>(g.edgeCount(), 0), most);
    CHECK_FALSE(isDiskRegion(g, std::vector<uint8_t>(g.edgeCount(), 0), most));
  }
  {  // two triangles of a square grid sharing one vertex only: a pinch
    const EdgeGraph g = buildEdgeGraph(testshapes::square(4));
    std::vector<uint32_t> fan;
    for (uint32_t f = 0; f < g.faceCount && fan.size() < 2; ++f)
      for (int c = 0; c < 3; ++c)
        if (g.faces[f][c] == 12 && (fan.empty() || g.faces[fan[0]][0] != g.faces[f][0])) {
          bool sharesEdge = false;
          for (const uint32_t h : fan)
            for (const uint32_t e : g.faceEdges[f]) sharesEdge |= g.edgeFaces[e][0] == h || g.edgeFaces[e][1] == h;
          if (!sharesEdge) fan.push_back(f);
          break;
        }
    REQUIRE(fan.size() == 2);
    agree(g, std::vector<uint8_t>(g.edgeCount(), 0), fan);
    CHECK_FALSE(isDiskRegion(g, std::vector<uint8_t>(g.edgeCount(), 0), fan));
  }
  CHECK(disks > 100);  // both answers were asked for
  CHECK(others > 100);
}
