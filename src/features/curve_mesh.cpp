#include "features/curve_mesh.h"
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
    size_t i = 0;
    double before = 0;  // integral up to the start of edge i
    for (uint32_t k = 1; k < n[c]; ++k) {
      double target = total * double(k) / double(n[c]);
      while (i + 1 < cu.edges.size() && before + edgeI[i] < target) before += edgeI[i++];
      uint32_t e = cu.edges[i], a = cu.vertices[i], b = cu.vertices[i + 1];
      double u = edgeParameter(g.edgeLength(e), s.h[a], s.h[b], target - before);  // from a to b
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
