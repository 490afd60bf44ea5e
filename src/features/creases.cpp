#include "features/creases.h"
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/status.h"
#include "core/union_find.h"

namespace conformesh::features {
namespace {


// Per candidate end (2·e + 0 at edgeVerts[e][0], 2·e + 1 at edgeVerts[e][1]): the candidate that
// continues it straightest at that vertex, or kNone. Pairs are matched greedily, smallest turn
// first (ties by edge ids), so each edge continues at most one other at each end.
std::vector<uint32_t> pairContinuations(const EdgeGraph& g, const std::vector<uint8_t>& candidate, double maxTurn) {
  std::vector<uint32_t> partner(2 * size_t(g.edgeCount()), kNone);
  std::vector<uint32_t> at;
  std::vector<std::tuple<double, uint32_t, uint32_t>> pairs;
  auto end = [&](uint32_t e, uint32_t v) { return 2 * e + (g.edgeVerts[e][0] == v ? 0u : 1u); };
  for (uint32_t v = 0; v < g.vertexCount; ++v) {
    at.clear();
    for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k)
      if (candidate[g.vertexEdgeIds[k]]) at.push_back(g.vertexEdgeIds[k]);
    if (at.size() < 2) continue;
    pairs.clear();
    for (size_t i = 0; i < at.size(); ++i)
      for (size_t j = i + 1; j < at.size(); ++j) {
        const Vec3 in = g.positions[v] - g.positions[g.otherVertex(at[i], v)];
        const Vec3 out = g.positions[g.otherVertex(at[j], v)] - g.positions[v];
        const double turn = angleBetween(in, out);
        if (turn <= maxTurn) pairs.emplace_back(turn, std::min(at[i], at[j]), std::max(at[i], at[j]));
      }
    std::sort(pairs.begin(), pairs.end());
    for (const auto& [turn, a, b] : pairs) {
      if (partner[end(a, v)] != kNone || partner[end(b, v)] != kNone) continue;
      partner[end(a, v)] = b;
      partner[end(b, v)] = a;
    }
  }
  return partner;
}

// The chains: candidates joined where one continues another (pairContinuations).
UnionFind chainsOf(const EdgeGraph& g, const std::vector<uint32_t>& partner) {
  UnionFind chain(g.edgeCount());
  for (uint32_t e = 0; e < g.edgeCount(); ++e)
    for (int k = 0; k < 2; ++k)
      if (partner[2 * e + k] != kNone) chain.unite(e, partner[2 * e + k]);
  return chain;
}

// A chain of many edges continuing each other straight over many output edges.
bool isLine(double length, uint32_t edges, const CreaseOptions& o) {
  return length >= o.lineLengthFactor * o.minLength && edges >= o.lineEdges;
}

// The outlier faces' candidate pairs (creases.h) made no candidates: those meeting below
// tipLimit whose faces across bend by at most limit, neither edge in keep; of a cap's pair
// whose faces across bend more (or with an edge in keep), the long edge, or the short one
// where the long one is in keep; and the candidate edge of a flap whose corners on it are below
// tipLimit, unless it is in keep. Decided from the candidates as given, so the result does not
// depend on the face order.
void dropOutlierFaces(const EdgeGraph& g, double limit, double tipLimit, const std::vector<uint8_t>& keep, Creases& out) {
  std::vector<uint32_t> drop;
  for (uint32_t f = 0; f < g.faceCount; ++f) {
    const auto& fe = g.faceEdges[f];
    for (int i = 0; i < 3; ++i) {  // a flap: its other two edges on the boundary
      const uint32_t e = fe[i];
      if (!out.edge[e] || keep[e] || !g.isBoundary(fe[(i + 1) % 3]) || !g.isBoundary(fe[(i + 2) % 3])) continue;
      if (g.cornerAngle(f, i) < tipLimit && g.cornerAngle(f, (i + 1) % 3) < tipLimit) drop.push_back(e);
    }
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        if (!out.edge[fe[i]] || !out.edge[fe[j]]) continue;
        const int tip = (3 - i - j + 2) % 3;  // the corner the two edges share
        if (g.cornerAngle(f, tip) >= tipLimit) continue;
        const uint32_t gi = g.edgeFaces[fe[i]][0] == f ? g.edgeFaces[fe[i]][1] : g.edgeFaces[fe[i]][0];
        const uint32_t gj = g.edgeFaces[fe[j]][0] == f ? g.edgeFaces[fe[j]][1] : g.edgeFaces[fe[j]][0];
        if (gi == kNone || gj == kNone || gi == gj) continue;
        const Vec3 ni = g.faceNormal(gi), nj = g.faceNormal(gj);
        if (norm(ni) == 0 || norm(nj) == 0) continue;
        if (!keep[fe[i]] && !keep[fe[j]] && angleBetween(ni, nj) <= limit) {
          drop.push_back(fe[i]);
          drop.push_back(fe[j]);
          continue;
        }
        // a cap: the long edge's far end is below tipLimit too, so the third corner is obtuse
        // and lies near the long edge, and the crease passing the sliver on both sides of it
        // is one crease: drop the long side, or the short one where the long edge is on a line
        const int longEdge = g.cornerAngle(f, i == tip ? (i + 1) % 3 : i) < tipLimit ? i
                             : g.cornerAngle(f, j == tip ? (j + 1) % 3 : j) < tipLimit ? j : -1;
        if (longEdge < 0) continue;
        const uint32_t longSide = fe[longEdge], shortSide = fe[longEdge == i ? j : i];
        if (!keep[longSide]) drop.push_back(longSide);
        else if (!keep[shortSide]) drop.push_back(shortSide);
      }
  }
  for (uint32_t e : drop)
    out.edge[e] = 0;
}

}  // namespace

Creases detectCreases(const EdgeGraph& g, const CreaseOptions& o) {
  if (!(o.featureAngleDeg >= 0 && o.featureAngleDeg <= 180))
    fail(Code::InvalidArgument, Stage::Segment, "featureAngle must be in [0, 180] degrees");
  if (!(o.minLength >= 0 && o.minLength < INFINITY))
    fail(Code::InvalidArgument, Stage::Segment, "minFeatureLength must be finite and >= 0");
  if (!(o.continuationDeg >= 0 && o.continuationDeg <= 180) || !(o.contrast >= 1) || !(o.strongContrast >= o.contrast) ||
      !(o.lineLengthFactor >= 1) || !(o.outlierTipDeg >= 0 && o.outlierTipDeg <= 180))
    fail(Code::InvalidArgument, Stage::Segment,
         "crease continuation and outlier tip in [0, 180], 1 <= contrast <= strongContrast, lineLengthFactor >= 1");
  const uint32_t ne = g.edgeCount();
  Creases out;
  out.edge.assign(ne, 0);
  std::vector<double> dihedral(ne, 0.0);
  const double limit = o.featureAngleDeg * kPi / 180.0;
  for (uint32_t e = 0; e < ne; ++e) {
    if (g.isBoundary(e)) continue;
    const Vec3 n0 = g.faceNormal(g.edgeFaces[e][0]), n1 = g.faceNormal(g.edgeFaces[e][1]);
    if (norm(n0) == 0 || norm(n1) == 0) continue;  // zero-area face: no meaningful dihedral angle
    dihedral[e] = angleBetween(n0, n1);
    if (dihedral[e] > limit) out.edge[e] = 1, ++out.candidates;
  }
  out.creaseEdges = out.candidates;
  if (o.minLength <= 0 || out.candidates == 0) return out;
  {  // outlier faces, but not on a line
    UnionFind chain = chainsOf(g, pairContinuations(g, out.edge, o.continuationDeg * kPi / 180.0));
    std::vector<double> length(ne, 0.0);
    std::vector<uint32_t> edges(ne, 0);
    for (uint32_t e = 0; e < ne; ++e)
      if (out.edge[e]) length[chain.find(e)] += g.edgeLength(e), ++edges[chain.find(e)];
    std::vector<uint8_t> onLine(ne, 0);
    for (uint32_t e = 0; e < ne; ++e)
      onLine[e] = out.edge[e] && isLine(length[chain.find(e)], edges[chain.find(e)], o);
    dropOutlierFaces(g, limit, o.outlierTipDeg * kPi / 180.0, onLine, out);
  }
  const std::vector<uint8_t> candidate = out.edge;

  const std::vector<uint32_t> partner = pairContinuations(g, candidate, o.continuationDeg * kPi / 180.0);
  UnionFind chain = chainsOf(g, partner);

  // contrast: the dihedral against the median of the other edges at both ends (the edge's own
  // continuations excluded: they are the crease, not its neighbourhood)
  std::vector<double> around;
  struct ChainStats {
    double length = 0, distinct = 0, strong = 0;  // the last two: length of edges that stand out
    uint32_t edges = 0;
    bool mostlyDistinct() const { return distinct >= 0.5 * length; }
    bool mostlyStrong() const { return strong >= 0.5 * length; }
  };
  std::vector<ChainStats> stats(ne);
  for (uint32_t e = 0; e < ne; ++e) {
    if (!candidate[e]) continue;
    around.clear();
    for (int k = 0; k < 2; ++k) {
      const uint32_t v = g.edgeVerts[e][k];
      for (uint32_t i = g.vertexEdgeStart[v]; i < g.vertexEdgeStart[v + 1]; ++i) {
        const uint32_t f = g.vertexEdgeIds[i];
        if (f != e && f != partner[2 * e + k] && !g.isBoundary(f)) around.push_back(dihedral[f]);
      }
    }
    double median = 0;
    if (!around.empty()) {
      std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
      median = around[around.size() / 2];
    }
    ChainStats& s = stats[chain.find(e)];
    const double len = g.edgeLength(e);
    s.length += len;
    ++s.edges;
    if (dihedral[e] >= o.contrast * median) s.distinct += len;
    if (dihedral[e] >= o.strongContrast * median) s.strong += len;
  }
  std::vector<uint8_t> keptChain(ne, 0);
  for (uint32_t e = 0; e < ne; ++e) {
    if (!candidate[e] || chain.find(e) != e) continue;
    ++out.chains;
    const ChainStats& s = stats[e];
    // a long chain that mostly stands out (three edges at least: one or two edges of a coarse
    // tessellation are no evidence of a line), or one that mostly stands out strongly, or a
    // line: many edges continuing each other straight over many output edges
    const bool line = isLine(s.length, s.edges, o);
    keptChain[e] = s.length >= o.minLength && ((s.mostlyDistinct() && s.edges >= 3) || s.mostlyStrong() || line);
  }
  // bridges: a short chain that mostly stands out and whose every free end touches another
  // kept or strongly standing-out chain, or the boundary, closes a region instead of dangling
  // in one (hysteresis: passes until none joins, capped). A network of short strong creases (a
  // small CAD part) holds itself up; an isolated strong edge of a coarse surface does not.
  std::vector<uint8_t> anchor(ne, 0);  // per chain root: kept, or strong
  for (uint32_t e = 0; e < ne; ++e)
    if (candidate[e] && chain.find(e) == e) anchor[e] = keptChain[e] || stats[e].mostlyStrong();
  auto touchesCurve = [&](uint32_t v, uint32_t root) {
    for (uint32_t i = g.vertexEdgeStart[v]; i < g.vertexEdgeStart[v + 1]; ++i) {
      const uint32_t f = g.vertexEdgeIds[i];
      if (g.isBoundary(f)) return true;
      if (candidate[f] && chain.find(f) != root && anchor[chain.find(f)]) return true;
    }
    return false;
  };
  std::vector<uint8_t> bridged(ne, 1);  // per chain root: every free end touches a curve
  for (int pass = 0; pass < 8; ++pass) {  // hard cap; each pass only adds chains
    std::fill(bridged.begin(), bridged.end(), 1);
    for (uint32_t e = 0; e < ne; ++e) {
      if (!candidate[e]) continue;
      const uint32_t r = chain.find(e);
      if (keptChain[r]) continue;
      for (int k = 0; k < 2; ++k)
        if (partner[2 * e + k] == kNone && !touchesCurve(g.edgeVerts[e][k], r)) bridged[r] = 0;
    }
    bool any = false;
    for (uint32_t e = 0; e < ne; ++e)
      if (candidate[e] && chain.find(e) == e && !keptChain[e] && bridged[e] && stats[e].mostlyDistinct())
        keptChain[e] = anchor[e] = 1, any = true;
    if (!any) break;
  }
  out.creaseEdges = 0;
  for (uint32_t e = 0; e < ne; ++e) {
    if (!candidate[e]) continue;
    out.edge[e] = keptChain[chain.find(e)];
    out.creaseEdges += out.edge[e];
    if (chain.find(e) == e) out.keptChains += keptChain[e];
  }
  return out;
}

}  // namespace conformesh::features
