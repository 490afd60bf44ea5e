#include "features/curve_mesh.h"
#include "core/constants.h"
#include "core/detmath.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace conformesh::features {
namespace {

// ∫ ds / h over an edge of length L where h goes linearly from h0 to h1.
double edgeIntegral(double L, double h0, double h1) {
  if (std::abs(h1 - h0) < 1e-12 * (h0 + h1)) return L / h0;
  return L * dmath::log(h1 / h0) / (h1 - h0);
}

// Parameter t in [0, 1] along an edge where ∫_0^t ds/h = I.
double edgeParameter(double L, double h0, double h1, double I) {
  if (std::abs(h1 - h0) < 1e-12 * (h0 + h1)) return std::clamp(I * h0 / L, 0.0, 1.0);
  double h = h0 * dmath::exp((h1 - h0) * I / L);
  return std::clamp((h - h0) / (h1 - h0), 0.0, 1.0);
}

uint32_t segmentCount(const EdgeGraph& g, const Curve& c, const SizingField& s) {
  double total = 0;
  for (size_t i = 0; i < c.edges.size(); ++i)
    total += edgeIntegral(g.edgeLength(c.edges[i]), s.h[c.vertices[i]], s.h[c.vertices[i + 1]]);
  return uint32_t(std::max<double>(1.0, std::round(total)));
}

// Walk curve cu (edgeI: ∫ ds/h per edge) forward from edge i, whose start is at integral
// `before`, to the edge holding integral `target`; returns the parameter there from
// cu.vertices[i] (a target at the edge's end is its end: a sample at a polyline vertex).
double walkTo(const EdgeGraph& g, const Curve& cu, const SizingField& s, const std::vector<double>& edgeI, double target,
              size_t& i, double& before) {
  while (i + 1 < cu.edges.size() && before + edgeI[i] < target) before += edgeI[i++];
  if (target >= before + edgeI[i] * (1 - 1e-12)) return 1.0;
  return edgeParameter(g.edgeLength(cu.edges[i]), s.h[cu.vertices[i]], s.h[cu.vertices[i + 1]], target - before);
}

// The point of curve cu at integral `target` of ds/h from its start.
Vec3 pointAt(const EdgeGraph& g, const Curve& cu, const SizingField& s, const std::vector<double>& edgeI, double target) {
  size_t i = 0;
  double before = 0;
  const double u = walkTo(g, cu, s, edgeI, target, i, before);
  return g.positions[cu.vertices[i]] * (1.0 - u) + g.positions[cu.vertices[i + 1]] * u;
}

// Would the chord from `corner` to `sample` (on the curve whose first vertex after the corner is
// `first`) leave the 3D angle to another curve's first edge at the corner below the bound, where
// the curve's own first edge keeps it at or above?
bool chordNarrowsCorner(const EdgeGraph& g, const Segmentation& seg, uint32_t corner, uint32_t first, const Vec3& sample) {
  const double bound = seg.angleBoundDeg * kPi / 180.0;
  const Vec3 edge = g.positions[first] - g.positions[corner], chord = sample - g.positions[corner];
  for (uint32_t k = g.vertexEdgeStart[corner]; k < g.vertexEdgeStart[corner + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k], w = g.otherVertex(e, corner);
    if (w == first || !seg.isCurveEdge(e)) continue;
    const Vec3 other = g.positions[w] - g.positions[corner];
    if (angleBetween(chord, other) < bound && angleBetween(edge, other) >= bound) return true;
  }
  return false;
}

}  // namespace

CurveMesh sampleCurves(const EdgeGraph& g, const Segmentation& seg, const SizingField& s) {
  CurveMesh cm;
  const size_t nC = seg.curves.size();
  std::vector<uint32_t> n(nC);
  for (size_t c = 0; c < nC; ++c) {
    n[c] = segmentCount(g, seg.curves[c], s);
    const auto& cv = seg.curves[c].vertices;
    if (cv.front() == cv.back()) n[c] = std::max<uint32_t>(n[c], 3);
  }
  // no two single-segment curves on the same pair of corners (their chords would coincide)
  std::map<std::pair<uint32_t, uint32_t>, size_t> single;
  for (size_t c = 0; c < nC; ++c) {
    if (n[c] != 1) continue;
    uint32_t a = seg.curves[c].vertices.front(), b = seg.curves[c].vertices.back();
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = single.find(key);
    if (it == single.end()) single.emplace(key, c);
    else n[c] = 2;
  }
  // every patch boundary has at least three segments
  std::vector<uint32_t> patchSegs(seg.patches.size(), 0), patchLongest(seg.patches.size(), kNone);
  for (size_t c = 0; c < nC; ++c)
    for (uint32_t p : seg.curves[c].patches) {
      if (p == kNone) continue;
      patchSegs[p] += n[c];
      if (patchLongest[p] == kNone || seg.curves[c].length > seg.curves[patchLongest[p]].length)
        patchLongest[p] = uint32_t(c);
    }
  for (size_t p = 0; p < patchSegs.size(); ++p)
    if (patchSegs[p] < 3 && patchLongest[p] != kNone) n[patchLongest[p]] += 3 - patchSegs[p];

  cm.cornerSample.assign(g.vertexCount, kNone);
  auto cornerId = [&](uint32_t v, uint32_t e) {
    if (cm.cornerSample[v] == kNone) {
      cm.cornerSample[v] = uint32_t(cm.samples.size());
      cm.samples.push_back({e, g.edgeVerts[e][0] == v ? 0.0 : 1.0, v, g.positions[v]});
    }
    return cm.cornerSample[v];
  };
  cm.curveSamples.resize(nC);
  for (size_t c = 0; c < nC; ++c) {
    const Curve& cu = seg.curves[c];
    auto& ids = cm.curveSamples[c];
    ids.push_back(cornerId(cu.vertices.front(), cu.edges.front()));
    double total = 0;
    std::vector<double> edgeI(cu.edges.size());
    for (size_t i = 0; i < cu.edges.size(); ++i) {
      edgeI[i] = edgeIntegral(g.edgeLength(cu.edges[i]), s.h[cu.vertices[i]], s.h[cu.vertices[i + 1]]);
      total += edgeI[i];
    }
    // where the samples fall along the curve (integrals of ds/h from its start)
    std::vector<double> at;
    for (uint32_t k = 1; k < n[c]; ++k) at.push_back(total * double(k) / double(n[c]));
    if (cu.edges.size() >= 2) {
      // a chord from a corner to a sample past the curve's first vertex, where the polyline
      // kinks, can close a wedge at the corner below the bound that the curve's first edge keeps
      // open (a cut turning towards a crease just after their junction): that vertex gets a
      // sample, so the chord is the first edge
      const double firstEnd = edgeI.front(), lastStart = total - edgeI.back();
      if ((at.empty() || at.front() > firstEnd) &&
          chordNarrowsCorner(g, seg, cu.vertices.front(), cu.vertices[1], pointAt(g, cu, s, edgeI, at.empty() ? total : at.front())))
        at.insert(at.begin(), firstEnd);
      if ((at.empty() || at.back() < lastStart) &&
          chordNarrowsCorner(g, seg, cu.vertices.back(), cu.vertices[cu.vertices.size() - 2],
                             pointAt(g, cu, s, edgeI, at.empty() ? 0.0 : at.back())))
        at.push_back(lastStart);
    }
    size_t i = 0;
    double before = 0;  // integral up to the start of edge i
    for (const double target : at) {
      const double u = walkTo(g, cu, s, edgeI, target, i, before);  // from a = cu.vertices[i]
      const uint32_t e = cu.edges[i], a = cu.vertices[i];
      CurveSample smp;
      smp.edge = e;
      smp.t = g.edgeVerts[e][0] == a ? u : 1.0 - u;
      const Vec3& p0 = g.positions[g.edgeVerts[e][0]];
      const Vec3& p1 = g.positions[g.edgeVerts[e][1]];
      if (smp.t <= 0.0) smp.vertex = g.edgeVerts[e][0], smp.t = 0.0;
      if (smp.t >= 1.0) smp.vertex = g.edgeVerts[e][1], smp.t = 1.0;
      smp.position = p0 * (1.0 - smp.t) + p1 * smp.t;
      ids.push_back(uint32_t(cm.samples.size()));
      cm.samples.push_back(smp);
    }
    ids.push_back(cornerId(cu.vertices.back(), cu.edges.back()));
  }
  return cm;
}

}  // namespace conformesh::features
