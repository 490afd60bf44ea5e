#include "remesh/curve_samples.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "conformal/flatten.h"
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

std::vector<InnerCurve> innerCurves(const Surface& surf, const F::PatchMesh& pm) {
  std::vector<InnerCurve> out;
  if (!surf.seg.innerCreases) return out;
  // per inner edge: the sub-mesh vertices at its two input vertices (edgeVerts order)
  std::unordered_map<uint32_t, std::array<uint32_t, 2>> subOfEdge;
  std::vector<uint32_t> curves;
  for (uint32_t t = 0; t < pm.faceInput.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t e = surf.g.faceEdges[pm.faceInput[t]][c], cv = surf.seg.edgeCurve[e];
      if (cv == kNone || !surf.seg.isInnerCurve(cv)) continue;
      const uint32_t a = pm.mesh.triangles[3 * t + c], b = pm.mesh.triangles[3 * t + (c + 1) % 3];
      const bool forward = pm.vertexInput[a] == surf.g.edgeVerts[e][0];
      if (subOfEdge.emplace(e, std::array<uint32_t, 2>{forward ? a : b, forward ? b : a}).second) curves.push_back(cv);
    }
  std::sort(curves.begin(), curves.end());
  curves.erase(std::unique(curves.begin(), curves.end()), curves.end());
  for (uint32_t cv : curves) {
    const F::Curve& cu = surf.seg.curves[cv];
    InnerCurve ic{cv, std::vector<uint32_t>(cu.vertices.size(), kNone)};
    for (size_t i = 0; i < cu.edges.size(); ++i) {
      const auto it = subOfEdge.find(cu.edges[i]);
      if (it == subOfEdge.end()) fail(Code::InternalError, Stage::CurveMesh, "an inner curve leaves its patch");
      const bool forward = surf.g.edgeVerts[cu.edges[i]][0] == cu.vertices[i];
      ic.sub[i] = it->second[forward ? 0 : 1];
      ic.sub[i + 1] = it->second[forward ? 1 : 0];
    }
    out.push_back(std::move(ic));
  }
  return out;
}

size_t loopPointCount(const std::vector<BoundaryPoint>& bp) {
  size_t n = 0;
  while (n < bp.size() && bp[n].inner == kNone) ++n;
  return n;
}

std::vector<BoundaryPoint> boundaryPoints(const Surface& surf, const CurveSamples& cs, const PatchWork& w,
                                          std::vector<InnerSegment>* inner) {
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
  if (inner) inner->clear();
  if (w.inner.empty()) return out;
  // the point at each sub-mesh vertex that has one: an inner curve ending on the loop, or two
  // inner curves meeting, share it
  std::unordered_map<uint32_t, uint32_t> atSub;
  for (uint32_t i = 0; i < out.size(); ++i)
    if (out[i].param == 0.0 && cs.cm.samples[out[i].sample].vertex != kNone) {
      const auto& h = loop[out[i].loopPos];
      atSub.emplace(w.pm.mesh.triangles[3 * h.face + h.corner], i);
    }
  for (uint32_t j = 0; j < w.inner.size(); ++j) {
    const InnerCurve& ic = w.inner[j];
    const auto& ids = cs.cm.curveSamples[ic.curve];
    const uint32_t n = uint32_t(surf.seg.curves[ic.curve].edges.size());
    uint32_t prev = kNone;
    double prevKey = 0;
    for (size_t q = 0; q < ids.size(); ++q) {
      // the ends by place (a closed curve's first and last sample are one)
      const double key = q == 0 ? 0.0 : q + 1 == ids.size() ? double(n) : curveKey(surf, cs, ic.curve, ids[q]);
      const uint32_t i = std::min(uint32_t(key), n - 1);
      const double t = key - double(i);
      uint32_t point = uint32_t(out.size());
      if (cs.cm.samples[ids[q]].vertex != kNone) {
        const uint32_t sub = ic.sub[t < 0.5 ? i : i + 1];
        const auto [it, fresh] = atSub.emplace(sub, point);
        if (fresh) out.push_back({ids[q], i, t, uv[2 * sub], uv[2 * sub + 1], j});
        point = it->second;
      } else {
        const uint32_t a = ic.sub[i], b = ic.sub[i + 1];
        // the flattening's map along the edge is projective (conformal/flatten.h): the point
        // at t on the input edge is at tp on the planar one
        const double tp = edgePlanarParam(w.flat.u, a, b, t);
        out.push_back({ids[q], i, t, uv[2 * a] + tp * (uv[2 * b] - uv[2 * a]), uv[2 * a + 1] + tp * (uv[2 * b + 1] - uv[2 * a + 1]), j});
      }
      if (prev != kNone && inner) inner->push_back({prev, point, j, prevKey, key});
      prev = point;
      prevKey = key;
    }
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
                        const std::vector<BoundaryPoint>& bp, const std::vector<InnerSegment>& inner,
                        uint32_t s, double t) {
  const auto& uv = w.flat.uv;
  const size_t loopPoints = loopPointCount(bp);
  // the stretch of polyline the segment spans, as pieces of input edges in the plane: of the loop
  // or of an inner curve
  const bool onLoop = s < loopPoints;
  if (!onLoop && s - loopPoints >= inner.size()) fail(Code::InternalError, Stage::Refine, "a split on no segment of the patch");
  const InnerSegment* sg = onLoop ? nullptr : &inner[s - loopPoints];
  const InnerCurve* ic = onLoop ? nullptr : &w.inner[sg->inner];
  const BoundaryPoint& p0 = onLoop ? bp[s] : bp[sg->a];
  const BoundaryPoint& p1 = onLoop ? bp[(s + 1) % loopPoints] : bp[sg->b];
  std::vector<Piece> pieces;
  if (onLoop) {
    pieces = stretch(w, p0, p1, loopPoints);
  } else {
    for (uint32_t i = uint32_t(sg->ka); i + 1 < ic->sub.size() && double(i) < sg->kb; ++i)
      pieces.push_back({i, std::max(0.0, sg->ka - double(i)), std::min(1.0, sg->kb - double(i))});
  }
  // the sub-mesh vertices at a piece's ends and the input edge it lies on, with its first vertex
  const auto pieceEnds = [&](uint32_t kk, uint32_t& a, uint32_t& b, uint32_t& e, uint32_t& A) {
    if (onLoop) {
      const auto& h = w.pm.boundaryLoops[0][kk];
      a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
      e = surf.g.faceEdges[w.pm.faceInput[h.face]][h.corner];
      A = w.pm.vertexInput[a];
    } else {
      a = ic->sub[kk], b = ic->sub[kk + 1];
      e = surf.seg.curves[ic->curve].edges[kk];
      A = surf.seg.curves[ic->curve].vertices[kk];
    }
  };
  // the planar point at parameter tt of piece kk's input edge (from its first vertex)
  auto pieceUv = [&](uint32_t kk, double tt, double& x, double& y) {
    uint32_t a, b, e, A;
    pieceEnds(kk, a, b, e, A);
    if (!onLoop) tt = edgePlanarParam(w.flat.u, a, b, tt);
    x = uv[2 * a] + tt * (uv[2 * b] - uv[2 * a]);
    y = uv[2 * a + 1] + tt * (uv[2 * b + 1] - uv[2 * a + 1]);
  };
  if (pieces.empty()) fail(Code::InternalError, Stage::Refine, "a split of a segment with no stretch of curve");
  std::vector<double> len(pieces.size());
  double total = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    double x0, y0, x1, y1;
    pieceUv(pieces[i].k, pieces[i].t0, x0, y0);
    pieceUv(pieces[i].k, pieces[i].t1, x1, y1);
    len[i] = dmath::hypot(x1 - x0, y1 - y0);
    total += len[i];
  }
  double target = t * total, acc = 0;
  size_t i = 0;
  while (i + 1 < pieces.size() && acc + len[i] < target) acc += len[i++];
  double local = len[i] > 0 ? std::clamp((target - acc) / len[i], 0.0, 1.0) : 0.5;
  uint32_t ea, eb, e, A;
  pieceEnds(pieces[i].k, ea, eb, e, A);
  // that fraction of the piece's planar length, on the input edge
  double th = pieces[i].t0 + local * (pieces[i].t1 - pieces[i].t0);
  if (!onLoop) {
    const double q0 = edgePlanarParam(w.flat.u, ea, eb, pieces[i].t0), q1 = edgePlanarParam(w.flat.u, ea, eb, pieces[i].t1);
    th = edgeSurfaceParam(w.flat.u, ea, eb, q0 + local * (q1 - q0));
  }
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
