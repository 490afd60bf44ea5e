#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "features/creases.h"
#include "features/edge_graph.h"
#include "features/sizing.h"
#include "features/test_shapes.h"
#include "features/data_models.h"
#include "mesh/mesh_io.h"

using namespace conformesh;
using namespace conformesh::features;

namespace {
// A sheet folded by `foldDeg` along x = 0.5 (n × n grid), lifted like roughSheet by `amplitude`.
MeshBuffers foldedSheet(int n, double foldDeg, double amplitude) {
  MeshBuffers m = testshapes::roughSheet(n, amplitude);
  const double t = std::tan(foldDeg * 3.14159265358979323846 / 180.0);
  for (size_t v = 0; v < m.positions.size() / 3; ++v) {
    const double x = m.positions[3 * v];
    if (x > 0.5) m.positions[3 * v + 2] += (x - 0.5) * t;
  }
  return m;
}

uint32_t creasesOnFold(const EdgeGraph& g, const Creases& c) {
  uint32_t n = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    if (c.edge[e] && std::abs(g.positions[g.edgeVerts[e][0]].x - 0.5) < 1e-12 && std::abs(g.positions[g.edgeVerts[e][1]].x - 0.5) < 1e-12) ++n;
  return n;
}
}  // namespace

TEST_CASE("creases: the facets of a rough coarse sheet are not creases; minLength 0 keeps every sharp edge") {
  EdgeGraph g = buildEdgeGraph(testshapes::roughSheet(16, 0.12));
  CreaseOptions all;
  const Creases every = detectCreases(g, all);
  REQUIRE(every.candidates > 40);  // the sheet is rough at 40°
  CHECK(every.creaseEdges == every.candidates);
  CreaseOptions o;
  o.minLength = 0.25;  // four grid edges
  const Creases c = detectCreases(g, o);
  MESSAGE("rough sheet: " << c.candidates << " sharp edges, " << c.chains << " chains, " << c.creaseEdges << " kept");
  CHECK(c.candidates == every.candidates);
  CHECK(c.creaseEdges * 10 <= c.candidates);
}

TEST_CASE("creases: a fold across a mildly rough sheet is kept whole, the roughness is not") {
  EdgeGraph g = buildEdgeGraph(foldedSheet(16, 70.0, 0.01));
  CreaseOptions o;
  o.minLength = 0.25;
  const Creases c = detectCreases(g, o);
  CHECK(creasesOnFold(g, c) == 16);  // every edge of the fold line
  CHECK(c.creaseEdges == 16);
  CHECK(c.keptChains == 1);
}

TEST_CASE("creases: a needle face tilted out of a flat sheet makes no crease; without the outlier test it does") {
  // triangle (a, b, c) of a flat grid split at p, just off the middle of ab and lifted: the
  // needle (a, b, p) tilts by about 79°, the faces around it by less than 10°
  MeshBuffers m = testshapes::square(8);
  const size_t t = 3 * 70;  // a triangle inside the grid
  const uint32_t a = m.triangles[t], b = m.triangles[t + 1], c = m.triangles[t + 2];
  double p[3];
  for (int k = 0; k < 3; ++k) {
    const double mid = 0.5 * (m.positions[3 * a + k] + m.positions[3 * b + k]);
    p[k] = mid + 0.02 * (m.positions[3 * c + k] - mid);
  }
  p[2] += 0.01;
  const uint32_t pi = uint32_t(m.vertexCount());
  m.positions.insert(m.positions.end(), p, p + 3);
  m.triangles[t + 2] = pi;
  m.triangles.insert(m.triangles.end(), {b, c, pi, c, a, pi});
  const EdgeGraph g = buildEdgeGraph(m);
  CreaseOptions o;
  o.minLength = 0.05;
  const Creases c0 = detectCreases(g, o);
  REQUIRE(c0.candidates >= 3);  // the needle's three edges
  CHECK(c0.creaseEdges == 0);
  o.outlierTipDeg = 0;
  CHECK(detectCreases(g, o).creaseEdges >= 2);
}

TEST_CASE("creases: a cap sliver on a fold leaves one crease past it, not one on each side") {
  // the fold of foldedSheet, and its fold edge (a, b) with the face on the left split at p, just
  // beside the middle of ab and lifted: the cap (a, b, p) has corners of about 20° at a and b, its
  // three edges are sharp, and both (a, b) and (a, p, b) would be creases meeting at a and b
  // below the bound: two exempt corners the surface does not have. The fold is a line at
  // minLength 0.25 (four times that is its length): it keeps (a, b); at 0.3 it is not, and
  // goes on through p.
  for (double minLength : {0.25, 0.3}) {
    MeshBuffers m = foldedSheet(16, 70.0, 0.0);
    size_t t = 0;
    int ia = -1;
    for (; t < m.triangles.size() && ia < 0; t += 3)
      for (int i = 0; i < 3 && ia < 0; ++i) {
        const double* pa = &m.positions[3 * m.triangles[t + i]];
        const double* pb = &m.positions[3 * m.triangles[t + (i + 1) % 3]];
        const double* pc = &m.positions[3 * m.triangles[t + (i + 2) % 3]];
        if (pa[0] == 0.5 && pb[0] == 0.5 && pc[0] < 0.5 && std::min(pa[1], pb[1]) > 0.4 && std::min(pa[1], pb[1]) < 0.6) ia = i;
      }
    REQUIRE(ia >= 0);
    t -= 3;
    const uint32_t a = m.triangles[t + ia], b = m.triangles[t + (ia + 1) % 3], c = m.triangles[t + (ia + 2) % 3];
    const double p[3] = {0.5 - 0.004, 0.5 * (m.positions[3 * a + 1] + m.positions[3 * b + 1]), 0.01};
    const uint32_t pi = uint32_t(m.vertexCount());
    m.positions.insert(m.positions.end(), p, p + 3);
    m.triangles[t + (ia + 2) % 3] = pi;
    m.triangles.insert(m.triangles.end(), {b, c, pi, c, a, pi});
    const EdgeGraph g = buildEdgeGraph(m);
    const uint32_t ab = g.findEdge(a, b), ap = g.findEdge(a, pi), bp = g.findEdge(b, pi);
    const Creases sharp = detectCreases(g, CreaseOptions{});  // every candidate
    REQUIRE((sharp.edge[ab] && sharp.edge[ap] && sharp.edge[bp]));
    CreaseOptions o;
    o.minLength = minLength;
    const Creases c0 = detectCreases(g, o);
    INFO("minLength " << minLength);
    const bool line = minLength < 0.26;
    CHECK(c0.edge[ab] == (line ? 1 : 0));
    CHECK(c0.edge[ap] == (line ? 0 : 1));
    CHECK(c0.edge[bp] == c0.edge[ap]);
    CHECK(creasesOnFold(g, c0) == 15 + c0.edge[ab]);  // the rest of the fold is kept
    CHECK(c0.creaseEdges == 16 + c0.edge[ap]);
    o.outlierTipDeg = 0;  // without the outlier tests both sides are kept
    const Creases c1 = detectCreases(g, o);
    CHECK(c1.edge[ab] + c1.edge[ap] + c1.edge[bp] == 3);
  }
}

TEST_CASE("creases: a sliver flap bent off the boundary makes no crease; a real tab does") {
  // a flat grid and one more face on a boundary edge (a, b), bent down by about 50°: a sliver
  // (corners of 14° at a and b) or a tab (corners of 68°)
  for (double offset : {0.01, 0.1}) {
    MeshBuffers m = testshapes::square(8);
    uint32_t a = kNone, b = kNone;
    for (size_t t = 0; t < m.triangles.size() && a == kNone; t += 3)
      for (int i = 0; i < 3; ++i) {
        const uint32_t u = m.triangles[t + i], v = m.triangles[t + (i + 1) % 3];
        if (m.positions[3 * u + 1] == 0 && m.positions[3 * v + 1] == 0 && m.positions[3 * u] > 0.3) a = u, b = v;
      }
    REQUIRE(a != kNone);
    const double q[3] = {0.5 * (m.positions[3 * a] + m.positions[3 * b]), -offset, -1.2 * offset};
    const uint32_t qi = uint32_t(m.vertexCount());
    m.positions.insert(m.positions.end(), q, q + 3);
    m.triangles.insert(m.triangles.end(), {b, a, qi});
    const EdgeGraph g = buildEdgeGraph(m);
    const uint32_t e = g.findEdge(a, b);
    CreaseOptions o;
    o.minLength = 0.5;
    const Creases c = detectCreases(g, o);
    REQUIRE(c.candidates == 1);
    INFO("offset " << offset);
    CHECK(c.edge[e] == (offset > 0.05 ? 1 : 0));
  }
}

TEST_CASE("creases: options out of range are InvalidArgument") {
  EdgeGraph g = buildEdgeGraph(testshapes::cube(2));
  CreaseOptions o;
  o.contrast = 0.5;
  CHECK_THROWS_AS(detectCreases(g, o), Error);
  o = CreaseOptions{};
  o.featureAngleDeg = 200;
  CHECK_THROWS_AS(detectCreases(g, o), Error);
  o = CreaseOptions{};
  o.minLength = -1;
  CHECK_THROWS_AS(detectCreases(g, o), Error);
  o = CreaseOptions{};
  o.outlierTipDeg = -1;
  CHECK_THROWS_AS(detectCreases(g, o), Error);
}

namespace {
EdgeGraph sharedModel(const char* name) { return buildEdgeGraph(testshapes::dataModel(name)); }
// Edges above 60° (the outside checker's sharp edges) that are creases, and how many there are.
std::pair<uint32_t, uint32_t> sharpKept(const EdgeGraph& g, const Creases& c) {
  uint32_t kept = 0, all = 0;
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    if (g.isBoundary(e) || angleBetween(g.faceNormal(g.edgeFaces[e][0]), g.faceNormal(g.edgeFaces[e][1])) <= 3.14159265358979323846 / 3) continue;
    ++all;
    kept += c.edge[e];
  }
  return {kept, all};
}
}  // namespace

TEST_CASE("creases: at the default length (2 % of the diagonal) CAD keeps its sharp edges, a coarse organic model drops most") {
  for (const char* name : {"fandisk.off", "camelhead.off", "man.off"}) {
    const EdgeGraph g = sharedModel(name);
    CreaseOptions o;
    o.minLength = 0.02 * boundingBoxDiagonal(g);
    CreaseOptions noLines = o;
    noLines.lineLengthFactor = 1e9;
    const auto [kept, all] = sharpKept(g, detectCreases(g, o));
    const uint32_t keptNoLines = sharpKept(g, detectCreases(g, noLines)).first;
    MESSAGE(std::string(name) << ": " << kept << " of " << all << " edges above 60 deg are creases (" << keptNoLines << " without the line rule)");
    if (std::string(name) == "fandisk.off") CHECK(kept == all);
    if (std::string(name) == "camelhead.off") CHECK(kept > keptNoLines);  // its long creases cross curved regions
    if (std::string(name) == "man.off") CHECK(2 * kept < all);
  }
}
