#include "remesh/curve_samples.h"

#include <algorithm>
#include <cmath>

#include "core/detmath.h"

namespace conformesh::pipeline {
namespace {

// Two splits of one input edge closer than this (in target edge lengths) are one sample.
constexpr double kSameSampleFactor = 1e-9;

}  // namespace

void indexSamples(const Surface& surf, CurveSamples& cs) {
  cs.edgeSamples.assign(surf.g.edgeCount(), {});
  cs.vertexSample.assign(surf.g.vertexCount, kNone);
  for (uint32_t s = 0; s < cs.cm.samples.size(); ++s) {
    const auto& smp = cs.cm.samples[s];
    if (smp.vertex != kNone) cs.vertexSample[smp.vertex] = s;
    else cs.edgeSamples[smp.edge].push_back(s);
  }
  cs.edgeIndexInCurve.assign(surf.g.edgeCount(), kNone);
  for (const auto& c : surf.seg.curves)
    for (uint32_t i = 0; i < c.edges.size(); ++i) cs.edgeIndexInCurve[c.edges[i]] = i;
}

std::vector<BoundaryPoint> boundaryPoints(const Surface& surf, const CurveSamples& cs, const PatchWork& w) {
  std::vector<BoundaryPoint> out;
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  for (uint32_t k = 0; k < loop.size(); ++k) {
    const auto& h = loop[k];
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    uint32_t A = w.pm.vertexInput[a];
    uint32_t e = surf.g.faceEdges[w.pm.faceInput[h.face]][h.corner];
    if (cs.vertexSample[A] != kNone) out.push_back({cs.vertexSample[A], k, 0.0, uv[2 * a], uv[2 * a + 1]});
    std::vector<std::pair<double, uint32_t>> on;
    for (uint32_t s : cs.edgeSamples[e]) {
      double t = cs.cm.samples[s].t;
      on.push_back({surf.g.edgeVerts[e][0] == A ? t : 1.0 - t, s});
    }
    std::sort(on.begin(), on.end());
    for (auto [t, s] : on)
      out.push_back({s, k, t, uv[2 * a] + t * (uv[2 * b] - uv[2 * a]), uv[2 * a + 1] + t * (uv[2 * b + 1] - uv[2 * a + 1])});
  }
  return out;
}

double curveKey(const Surface& surf, const CurveSamples& cs, uint32_t c, uint32_t s) {
  const auto& cu = surf.seg.curves[c];
  const auto& ids = cs.cm.curveSamples[c];
  if (s == ids.front()) return 0.0;
  if (s == ids.back()) return double(cu.edges.size());
  const auto& smp = cs.cm.samples[s];
  uint32_t e = smp.edge;
  uint32_t i = cs.edgeIndexInCurve[e];
  double t = cu.vertices[i] == surf.g.edgeVerts[e][0] ? smp.t : 1.0 - smp.t;
  return double(i) + t;
}

std::vector<Piece> stretch(const PatchWork& w, const BoundaryPoint& p0, const BoundaryPoint& p1, size_t points) {
  const auto& loop = w.pm.boundaryLoops[0];
  std::vector<Piece> pieces;
  uint32_t k = p0.loopPos;
  double from = p0.param;
  for (size_t guard = 0; guard <= loop.size() + 1; ++guard) {
    if (k == p1.loopPos && (p1.param >= from || pieces.size() > 0 || points > 1)) {
      if (!(k == p0.loopPos && pieces.empty() && p1.param < from)) {
        pieces.push_back({k, from, p1.param});
        break;
      }
    }
    pieces.push_back({k, from, 1.0});
    k = (k + 1) % uint32_t(loop.size());
    from = 0.0;
  }
  return pieces;
}

uint32_t addSplitSample(const Surface& surf, CurveSamples& cs, Patches& patches, const PatchWork& w,
                        const std::vector<BoundaryPoint>& bp, uint32_t s, double t) {
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  const BoundaryPoint& p0 = bp[s];
  const BoundaryPoint& p1 = bp[(s + 1) % bp.size()];
  const std::vector<Piece> pieces = stretch(w, p0, p1, bp.size());
  auto halfedgeUv = [&](uint32_t kk, double tt, double& x, double& y) {
    const auto& h = loop[kk];
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    x = uv[2 * a] + tt * (uv[2 * b] - uv[2 * a]);
    y = uv[2 * a + 1] + tt * (uv[2 * b + 1] - uv[2 * a + 1]);
  };
  std::vector<double> len(pieces.size());
  double total = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    double x0, y0, x1, y1;
    halfedgeUv(pieces[i].k, pieces[i].t0, x0, y0);
    halfedgeUv(pieces[i].k, pieces[i].t1, x1, y1);
    len[i] = dmath::hypot(x1 - x0, y1 - y0);
    total += len[i];
  }
  double target = t * total, acc = 0;
  size_t i = 0;
  while (i + 1 < pieces.size() && acc + len[i] < target) acc += len[i++];
  double local = len[i] > 0 ? std::clamp((target - acc) / len[i], 0.0, 1.0) : 0.5;
  double th = pieces[i].t0 + local * (pieces[i].t1 - pieces[i].t0);
  const auto& h = loop[pieces[i].k];
  uint32_t A = w.pm.vertexInput[w.pm.mesh.triangles[3 * h.face + h.corner]];
  uint32_t e = surf.g.faceEdges[w.pm.faceInput[h.face]][h.corner];
  F::CurveSample smp;
  smp.edge = e;
  smp.t = surf.g.edgeVerts[e][0] == A ? th : 1.0 - th;
  // A split must add a point strictly inside this stretch, never one of its ends: where it
  // falls on an end (a stretch between two samples closer than the dedupe resolution, as two
  // input corners a rounding error apart give), it goes to the middle of its piece instead.
  const bool onEnd = smp.t <= 0.0 || smp.t >= 1.0;
  const uint32_t endSample = onEnd ? cs.vertexSample[smp.t <= 0.0 ? surf.g.edgeVerts[e][0] : surf.g.edgeVerts[e][1]] : kNone;
  if (onEnd && (endSample == p0.sample || endSample == p1.sample) && pieces[i].t1 > pieces[i].t0) {
    th = 0.5 * (pieces[i].t0 + pieces[i].t1);
    smp.t = surf.g.edgeVerts[e][0] == A ? th : 1.0 - th;
  }
  if (smp.t <= 0.0 || smp.t >= 1.0) {
    uint32_t v = smp.t <= 0.0 ? surf.g.edgeVerts[e][0] : surf.g.edgeVerts[e][1];
    if (cs.vertexSample[v] != kNone) {
      if (cs.vertexSample[v] == p0.sample || cs.vertexSample[v] == p1.sample)
        fail(Code::InternalError, Stage::Refine, "a boundary stretch has no length to split");
      return cs.vertexSample[v];
    }
    smp.t = smp.t <= 0.0 ? 0.0 : 1.0;
    smp.vertex = v;
  }
  // a seam (a cut with the patch on both sides) is split at the same place from both sides:
  // one sample for both (but never an end of this stretch)
  if (smp.vertex == kNone)
    for (uint32_t o : cs.edgeSamples[e])
      if (std::abs(cs.cm.samples[o].t - smp.t) * surf.g.edgeLength(e) < kSameSampleFactor * surf.sizing.target &&
          o != p0.sample && o != p1.sample)
        return o;
  smp.position = surf.g.positions[surf.g.edgeVerts[e][0]] * (1.0 - smp.t) + surf.g.positions[surf.g.edgeVerts[e][1]] * smp.t;
  uint32_t id = uint32_t(cs.cm.samples.size());
  cs.cm.samples.push_back(smp);
  if (smp.vertex != kNone) cs.vertexSample[smp.vertex] = id;
  else cs.edgeSamples[e].push_back(id);
  uint32_t c = surf.seg.edgeCurve[e];
  if (c == kNone) fail(Code::InternalError, Stage::Refine, "a patch boundary edge is on no curve");
  auto& ids = cs.cm.curveSamples[c];
  double key = curveKey(surf, cs, c, id);
  size_t pos = 1;
  while (pos + 1 < ids.size() && curveKey(surf, cs, c, ids[pos]) < key) ++pos;
  ids.insert(ids.begin() + long(pos), id);
  ++cs.stamp;
  for (uint32_t q : surf.seg.curves[c].patches)
    if (q != kNone && patches[q]->builtAt < cs.stamp) patches[q]->dirty = true;
  return id;
}

}  // namespace conformesh::pipeline
