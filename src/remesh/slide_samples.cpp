#include "remesh/slide_samples.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/detmath.h"
#include "core/vertex_stars.h"
#include "planar/predicates.h"
#include "remesh/curve_samples.h"

namespace conformesh::pipeline {

std::vector<std::vector<uint8_t>> slideSamples(const Surface& surf, const RemeshOptions& opt, Meshing& m, RemeshReport& rep) {
  Patches& work = m.patches;
  std::vector<std::vector<uint8_t>> slid(work.size());
  const size_t nS = m.samples.cm.samples.size();
  const double bound = opt.minAngle;
  struct Hold {
    uint32_t p, v;
  };
  // per patch: vertex -> triangles (CSR), cached 3D min angle per triangle, and per input edge
  // the boundary loop halfedges that lie on it
  struct Star {
    std::vector<uint32_t> start, tri;
    std::vector<double> minAngle;
    std::vector<std::pair<uint32_t, uint32_t>> loopOfEdge;  // (input edge, loop halfedge), sorted
  };
  std::vector<Star> stars(work.size());
  std::vector<std::vector<Hold>> holds(nS);
  auto pos3 = [&](const PatchWork& w, uint32_t v) -> const Vec3& {
    return w.localToGlobal[v] != kNone ? m.samples.cm.samples[w.localToGlobal[v]].position : w.interiorPositions[v];
  };
  for (uint32_t p = 0; p < work.size(); ++p) {
    const PatchWork& w = *work[p];
    Star& st = stars[p];
    const size_t nv = w.localToGlobal.size(), nt = w.triangles.size() / 3;
    // the latest optimization's stars when it left them (the same triangles)
    if (work[p]->optimizeCache.starStart.size() == nv + 1) {
      st.start.swap(work[p]->optimizeCache.starStart);
      st.tri.swap(work[p]->optimizeCache.starTri);
    } else {
      vertexStars(w.triangles, nv, st.start, st.tri);
    }
    // the patch's latest optimization left these very values (minAngleDeg3Approx of the same
    // positions: only optimizations and slides move vertices, and each keeps them current; a
    // slide stores the exact values of the stars it changed, within 1e-5 degrees of those)
    if (work[p]->optimizeCache.minAngle.size() == nt) {
      st.minAngle.swap(work[p]->optimizeCache.minAngle);
    } else {
      st.minAngle.resize(nt);
      for (size_t t = 0; t < nt; ++t)
        st.minAngle[t] = optimization::minAngleDeg3Approx(pos3(w, w.triangles[3 * t]), pos3(w, w.triangles[3 * t + 1]), pos3(w, w.triangles[3 * t + 2]));
    }
    const auto& loop = w.pm.boundaryLoops[0];
    for (uint32_t k = 0; k < loop.size(); ++k) st.loopOfEdge.push_back({surf.g.faceEdges[w.pm.faceInput[loop[k].face]][loop[k].corner], k});
    std::sort(st.loopOfEdge.begin(), st.loopOfEdge.end());
    for (uint32_t v = 0; v < nv; ++v)
      if (w.localToGlobal[v] != kNone) holds[w.localToGlobal[v]].push_back({p, v});
  }
  // planar position in patch w of the point at parameter t of input edge e, on loop halfedge k
  auto planarAt = [&](const PatchWork& w, uint32_t k, uint32_t e, double t, double out[2]) {
    const auto& h = w.pm.boundaryLoops[0][k];
    const uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    const double tt = surf.g.edgeVerts[e][0] == w.pm.vertexInput[a] ? t : 1.0 - t;
    const auto& uv = w.flat.uv;
    out[0] = uv[2 * a] + tt * (uv[2 * b] - uv[2 * a]);
    out[1] = uv[2 * a + 1] + tt * (uv[2 * b + 1] - uv[2 * a + 1]);
  };
  constexpr int kPasses = 2;  // hard cap
  std::vector<double> fresh;
  std::vector<std::array<double, 2>> newXY;
  std::vector<uint32_t> loopK, nb;
  // a sample is tried again in the next pass when a sample of its star slid
  std::vector<uint8_t> activeS(nS, 1), nextS(nS, 0);
  for (int pass = 0; pass < kPasses; ++pass) {
    size_t slides = 0;
    std::fill(nextS.begin(), nextS.end(), 0);
    for (uint32_t s = 0; s < nS; ++s) {
      F::CurveSample& smp = m.samples.cm.samples[s];
      if (!activeS[s] || smp.vertex != kNone || smp.edge == kNone || holds[s].empty()) continue;
      const uint32_t e = smp.edge;
      // the free interval on the edge: up to the nearest samples on it (or its ends)
      double lo = 0, hi = 1;
      for (uint32_t o : m.samples.edgeSamples[e]) {
        if (o == s) continue;
        const double to = m.samples.cm.samples[o].t;
        if (to < smp.t) lo = std::max(lo, to);
        else hi = std::min(hi, to);
      }
      // the sample's neighbours along its curve: the other ends of its boundary edges in the
      // first patch that holds it (an edge of one triangle only)
      const Hold h0 = holds[s][0];
      const PatchWork& w0 = *work[h0.p];
      const Star& st0 = stars[h0.p];
      nb.clear();
      for (uint32_t i = st0.start[h0.v]; i < st0.start[h0.v + 1]; ++i) {
        const uint32_t* t = &w0.triangles[3 * size_t(st0.tri[i])];
        for (int c = 0; c < 3; ++c)
          if (t[c] == h0.v) {
            nb.push_back(t[(c + 1) % 3]);
            nb.push_back(t[(c + 2) % 3]);
          }
      }
      std::sort(nb.begin(), nb.end());
      Vec3 mid{0, 0, 0};
      uint32_t endSample[2] = {kNone, kNone};
      int ends = 0;
      for (size_t i = 0; i < nb.size(); ++i) {
        const bool single = (i == 0 || nb[i - 1] != nb[i]) && (i + 1 == nb.size() || nb[i + 1] != nb[i]);
        if (single && w0.localToGlobal[nb[i]] != kNone) {
          mid = mid + pos3(w0, nb[i]);
          if (ends < 2) endSample[ends] = w0.localToGlobal[nb[i]];
          ++ends;
        }
      }
      if (ends != 2) continue;
      mid = mid * 0.5;
      // the input curve between the two neighbours: its vertices must not end up farther from
      // the chords than they are now (the slide keeps the curve's chordal deviation)
      const uint32_t cv = surf.seg.edgeCurve[e];
      if (cv == kNone) continue;
      const auto& cids = m.samples.cm.curveSamples[cv];
      if (cids.front() == cids.back() && (endSample[0] == cids.front() || endSample[1] == cids.front())) continue;
      double kPrev = curveKey(surf, m.samples, cv, endSample[0]), kNext = curveKey(surf, m.samples, cv, endSample[1]);
      if (kPrev > kNext) std::swap(kPrev, kNext), std::swap(endSample[0], endSample[1]);
      const double kSelf = curveKey(surf, m.samples, cv, s);
      if (!(kPrev < kSelf && kSelf < kNext)) continue;
      const auto& cverts = surf.seg.curves[cv].vertices;
      auto segDist = [](const Vec3& p, const Vec3& a, const Vec3& b) {
        const Vec3 ab = b - a;
        const double l = dot(ab, ab);
        const double u = l > 0 ? std::clamp(dot(p - a, ab) / l, 0.0, 1.0) : 0.0;
        return norm(p - (a + ab * u));
      };
      auto deviation = [&](const Vec3& S, double kS) {
        double d = 0;
        for (size_t i = size_t(std::floor(kPrev)) + 1; i < cverts.size() && double(i) < kNext; ++i) {
          const Vec3& X = surf.g.positions[cverts[i]];
          d = std::max(d, double(i) < kS ? segDist(X, m.samples.cm.samples[endSample[0]].position, S) : segDist(X, S, m.samples.cm.samples[endSample[1]].position));
        }
        return d;
      };
      const double devOld = deviation(smp.position, kSelf);
      const Vec3 A = surf.g.positions[surf.g.edgeVerts[e][0]], B = surf.g.positions[surf.g.edgeVerts[e][1]], AB = B - A;
      const double l2 = dot(AB, AB);
      if (!(l2 > 0)) continue;
      // stay clear of the neighbouring samples on the edge by a tenth of the free interval
      const double margin = 0.1 * (hi - lo);
      const double target = std::clamp(dot(mid - A, AB) / l2, lo + margin, hi - margin);
      // the loop halfedge of each hold: the one on edge e whose point at t is where the sample is
      loopK.assign(holds[s].size(), kNone);
      for (size_t i = 0; i < holds[s].size(); ++i) {
        const PatchWork& w = *work[holds[s][i].p];
        const auto& loe = stars[holds[s][i].p].loopOfEdge;
        const auto range = std::equal_range(loe.begin(), loe.end(), std::pair<uint32_t, uint32_t>{e, 0},
                                            [](const auto& a, const auto& b) { return a.first < b.first; });
        double best = INFINITY;
        for (auto it = range.first; it != range.second; ++it) {
          const uint32_t k = it->second;
          double q[2];
          planarAt(w, k, e, smp.t, q);
          const double d = dmath::hypot(q[0] - w.planarPoints[2 * holds[s][i].v], q[1] - w.planarPoints[2 * holds[s][i].v + 1]);
          if (d < best) best = d, loopK[i] = k;
        }
      }
      if (std::find(loopK.begin(), loopK.end(), kNone) != loopK.end()) continue;
      // a seam (a cut with the same patch on both sides) whose two stars share a triangle: the
      // angles of that triangle would be judged with one copy moved at a time
      bool shared = false;
      for (size_t i = 0; i < holds[s].size() && !shared; ++i)
        for (size_t j = i + 1; j < holds[s].size() && !shared; ++j) {
          const Hold &a = holds[s][i], &b = holds[s][j];
          if (a.p != b.p) continue;
          for (uint32_t x = stars[a.p].start[a.v]; x < stars[a.p].start[a.v + 1] && !shared; ++x)
            for (uint32_t y = stars[b.p].start[b.v]; y < stars[b.p].start[b.v + 1] && !shared; ++y)
              shared = stars[a.p].tri[x] == stars[b.p].tri[y];
        }
      if (shared) continue;
      double oldMin = 180, oldSum = 0;
      for (const Hold& hd : holds[s])
        for (uint32_t i = stars[hd.p].start[hd.v]; i < stars[hd.p].start[hd.v + 1]; ++i) {
          const double a = stars[hd.p].minAngle[stars[hd.p].tri[i]];
          oldMin = std::min(oldMin, a);
          oldSum += a;
        }
      // a star with a triangle under the bound does not slide: which of those triangles an exempt
      // corner owns depends on where the curve samples are (see exemptCornerOf)
      if (oldMin < bound) continue;
      const double floor = bound;
      // evaluate a candidate parameter: false when it is refused (the rule of the header comment)
      // (exact: with the exact angles; else with minAngleDeg3Approx, within 1e-4 degrees, to rank)
      auto evaluate = [&](double t, bool exact, double& newMin, double& newSum, std::vector<double>& angles, std::vector<std::array<double, 2>>& xy) {
        if (!(t > lo && t < hi) || t == smp.t) return false;
        const Vec3 P = A * (1.0 - t) + B * t;
        if (deviation(P, kSelf) > devOld) return false;  // the side of each curve vertex does not change within the edge
        newMin = 180, newSum = 0;
        angles.clear();
        xy.assign(holds[s].size(), {0, 0});
        for (size_t i = 0; i < holds[s].size(); ++i) {
          const Hold& hd = holds[s][i];
          const PatchWork& w = *work[hd.p];
          planarAt(w, loopK[i], e, t, xy[i].data());
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j) {
            const uint32_t* tv = &w.triangles[3 * size_t(stars[hd.p].tri[j])];
            const double* c[3];
            Vec3 q[3];
            for (int k = 0; k < 3; ++k) {
              c[k] = tv[k] == hd.v ? xy[i].data() : &w.planarPoints[2 * size_t(tv[k])];
              q[k] = tv[k] == hd.v ? P : pos3(w, tv[k]);
            }
            const double e2 = std::max({(c[1][0] - c[0][0]) * (c[1][0] - c[0][0]) + (c[1][1] - c[0][1]) * (c[1][1] - c[0][1]),
                                        (c[2][0] - c[1][0]) * (c[2][0] - c[1][0]) + (c[2][1] - c[1][1]) * (c[2][1] - c[1][1]),
                                        (c[0][0] - c[2][0]) * (c[0][0] - c[2][0]) + (c[0][1] - c[2][1]) * (c[0][1] - c[2][1])});
            if (!(planar::orient2d(c[0], c[1], c[2]) > 1e-6 * e2)) return false;
            const double a = exact ? optimization::minAngleDeg3(q[0], q[1], q[2]) : optimization::minAngleDeg3Approx(q[0], q[1], q[2]);
            if (!(a >= 0)) return false;  // NaN: a degenerate corner
            angles.push_back(a);
            newMin = std::min(newMin, a);
            newSum += a;
          }
        }
        return newMin >= floor && newSum > oldSum + 1e-9 * double(angles.size());
      };
      // candidates: toward the midpoint (full and half step), and evenly over the free interval
      // (no lift is needed on a curve, so a search is cheap); the best kept one wins
      constexpr int kSpread = 6;
      double cand[2 + kSpread] = {target, 0.5 * (smp.t + target)};
      for (int i = 0; i < kSpread; ++i) cand[2 + i] = lo + margin + (hi - lo - 2 * margin) * (i + 0.5) / kSpread;
      double bestT = -1, bestSum = -INFINITY;
      for (const double t : cand) {
        double mn, sm;
        if (evaluate(t, false, mn, sm, fresh, newXY) && sm > bestSum) bestSum = sm, bestT = t;
      }
      double mn, sm;
      if (bestT < 0 || !evaluate(bestT, true, mn, sm, fresh, newXY)) continue;
      {
        const double t = bestT;
        const Vec3 P = A * (1.0 - t) + B * t;
        smp.t = t;
        smp.position = P;
        size_t f = 0;
        for (size_t i = 0; i < holds[s].size(); ++i) {
          const Hold& hd = holds[s][i];
          PatchWork& w = *work[hd.p];
          w.planarPoints[2 * size_t(hd.v)] = newXY[i][0];
          w.planarPoints[2 * size_t(hd.v) + 1] = newXY[i][1];
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j) stars[hd.p].minAngle[stars[hd.p].tri[j]] = fresh[f++];
          // the star's vertices may move again now
          if (slid[hd.p].empty()) slid[hd.p].assign(w.localToGlobal.size(), 0);
          for (uint32_t j = stars[hd.p].start[hd.v]; j < stars[hd.p].start[hd.v + 1]; ++j)
            for (int c = 0; c < 3; ++c) {
              const uint32_t u = w.triangles[3 * size_t(stars[hd.p].tri[j]) + c];
              slid[hd.p][u] = 1;
              if (w.localToGlobal[u] != kNone) nextS[w.localToGlobal[u]] = 1;
            }
        }
        ++slides;
      }
    }
    rep.optimizeMoves += slides;
    if (slides == 0) break;
    activeS.swap(nextS);
  }
  // the min angles, kept exact through the slides, go back for the next optimization
  // so do the stars
  for (uint32_t p = 0; p < work.size(); ++p) {
    work[p]->optimizeCache.minAngle.swap(stars[p].minAngle);
    work[p]->optimizeCache.starStart.swap(stars[p].start);
    work[p]->optimizeCache.starTri.swap(stars[p].tri);
  }
  return slid;
}

}  // namespace conformesh::pipeline
