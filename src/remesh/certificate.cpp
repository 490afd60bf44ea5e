#include "remesh/certificate.h"
#include "core/constants.h"

#include <cmath>

#include "core/detmath.h"
#include "core/parallel_for.h"
#include "quality/metrics.h"
#include "remesh/stitch_defects.h"

namespace conformesh::pipeline {
namespace {


}  // namespace

double triangleMinAngle(const MeshBuffers& m, size_t t) {
  double mn, mx;
  return quality::minMaxAngle(m, t, mn, mx) ? mn * 180.0 / kPi : 0.0;
}

bool minAngleBelow(const MeshBuffers& m, size_t t, double boundDeg, double cosBound) {
  Vec3 p[3];
  for (int c = 0; c < 3; ++c) p[c] = vec3At(m.positions, m.triangles[3 * t + c]);
  constexpr double kApart = 1e-9;
  bool above = true;
  for (int c = 0; c < 3; ++c) {
    const Vec3 u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
    const double uu = dot(u, u), vv = dot(v, v);
    if (!(uu >= 1e-200 && uu <= 1e200 && vv >= 1e-200 && vv <= 1e200)) return triangleMinAngle(m, t) < boundDeg;
    const double cosA = dot(u, v) / (std::sqrt(uu) * std::sqrt(vv));
    if (cosA > cosBound + kApart) return true;
    above = above && cosA < cosBound - kApart;
  }
  return above ? false : triangleMinAngle(m, t) < boundDeg;
}

//! How the output's topology differs from the input's ("Euler characteristic 3 vs 2, 1
//! non-manifold edge"), or "" when it has the input's components, boundary loops and Euler

void measureCorners(const Surface& surf, double boundDeg, Meshing& m) {
  const std::vector<double> wedge = F::featureWedgeAngles(surf.g, surf.seg);
  m.cornerWedgeDeg.resize(wedge.size());
  m.smallCorner.assign(wedge.size(), 0);
  for (uint32_t v = 0; v < wedge.size(); ++v) {
    m.cornerWedgeDeg[v] = wedge[v] * 180.0 / kPi;
    // the preconditioner's split vertices are no corners of the input
    m.smallCorner[v] = v < surf.input().vertexCount() && m.cornerWedgeDeg[v] < boundDeg;
  }
}

ExemptCorners::ExemptCorners(double bound) : boundDeg(bound), cosBound(dmath::cos(bound * kPi / 180.0)) {}

void ExemptCorners::find(const Surface& surf, const Meshing& m, size_t outVertices, RemeshReport& rep) {
  vertex.assign(outVertices, 0);
  rep.exemptCorners.clear();
  const F::CurveMesh& cm = m.samples.cm;
  for (uint32_t iv = 0; iv < m.smallCorner.size(); ++iv) {
    if (!m.smallCorner[iv]) continue;
    uint32_t s = iv < cm.cornerSample.size() ? cm.cornerSample[iv] : kNone;
    if (s == kNone || s >= vertex.size() || vertex[s]) continue;
    vertex[s] = 1;
    wedgeDeg[s] = m.cornerWedgeDeg[iv];
    rep.exemptCorners.push_back({surf.vm.vertexToInput[iv], s, m.cornerWedgeDeg[iv], {}});
  }
}

void ExemptCorners::indexWedges(const Surface& surf, const CurveSamples& cs) {
  wedgeCurves.assign(cs.cm.samples.size(), {});
  for (uint32_t c = 0; c < surf.seg.curves.size(); ++c) {
    const auto& ids = cs.cm.curveSamples[c];
    for (uint32_t corner : {ids.front(), ids.back()}) {
      if (corner >= vertex.size() || !vertex[corner]) continue;
      for (uint32_t s : ids)
        if (s != corner) wedgeCurves[s].push_back({corner, c});
      if (ids.front() == ids.back()) break;  // a closed curve: once
    }
  }
}

// The exempt corner triangle t belongs to, or kNone: it touches the corner, or one of its edges
// spans the corner's small wedge: its ends lie on two different curves that meet at the corner,
// at distances from it within a factor 2 of each other, and it is seen from the corner under an
// angle between half the corner's wedge angle and the bound. Ruppert's concentric shells leave
// such skinny triangles there, whose angle the input forces (the "seditious edges" of Shewchuk
// 2002). Where the two curves stop diverging (a long strip between them), an edge across is
// seen under less and less: not exempt.
uint32_t ExemptCorners::cornerOf(const MeshBuffers& out, size_t t) const {
  const uint32_t* tv = &out.triangles[3 * t];
  for (int c = 0; c < 3; ++c)
    if (vertex[tv[c]]) return tv[c];
  auto pos = [&](uint32_t v) { return vec3At(out.positions, v); };
  for (int c = 0; c < 3; ++c) {
    const uint32_t a = tv[c], b = tv[(c + 1) % 3];
    if (a >= wedgeCurves.size() || b >= wedgeCurves.size()) continue;
    for (const auto& [ca, cua] : wedgeCurves[a])
      for (const auto& [cb, cub] : wedgeCurves[b]) {
        if (ca != cb || cua == cub) continue;
        const Vec3 p = pos(ca), da = pos(a) - p, db = pos(b) - p;
        const double la = norm(da), lb = norm(db), seen = F::angleBetween(da, db) * 180.0 / kPi;
        if (la <= 2 * lb && lb <= 2 * la && seen < boundDeg && seen >= 0.5 * wedgeDeg.at(ca)) return ca;
      }
  }
  return kNone;
}

Verdict judge(const MeshBuffers& out, const std::vector<uint32_t>& triPatch, const ExemptCorners& exempt,
              unsigned threads) {
  const double cosCollapsed = dmath::cos(kCollapsedDeg * kPi / 180.0);
  Verdict v;
  parallelFor(3, threads, [&](size_t pass) {
    if (pass == 0) {
      // bad: below the bound outside exempt corners; collapsed: a corner below kCollapsedDeg
      // (points closer than the lift resolves, e.g. refinement cascading into a small exempt wedge)
      for (size_t t = 0; t < out.triangleCount(); ++t) {
        if (minAngleBelow(out, t, kCollapsedDeg, cosCollapsed)) ++v.collapsed;
        if (exempt.bad(out, t)) ++v.bad;
      }
    } else if (pass == 1) {
      // the same three samples meshed as a triangle by two patches (a corner wedge between two
      // curves that both patches border, closed by one triangle on each side), or a chord both
      // have: the stitched surface is not manifold there
      v.doubled = doubledTriangles(out, triPatch);
    } else {
      v.chords = sharedChords(out, triPatch);
    }
  });
  return v;
}

void requestRefinement(const Verdict& verdict, const MeshBuffers& out, const std::vector<uint32_t>& triPatch,
                       const ExemptCorners& exempt, bool keepBoundary, Patches& patches) {
  std::vector<size_t> firstTri(patches.size(), 0);  // each patch's first triangle in out
  for (size_t i = triPatch.size(); i-- > 0;) firstTri[triPatch[i]] = i;
  // A doubled triangle closes a corner wedge of its patch alone: the patch must put a vertex
  // inside it, halfway from the wedge's corner (its largest angle) to the far side; a finer
  // size there would only split the two curves and close the wedge again one step closer.
  for (size_t t : verdict.doubled) {
    PatchWork& w = *patches[triPatch[t]];
    const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
    const double* q[3] = {&w.planarPoints[2 * lt[0]], &w.planarPoints[2 * lt[1]], &w.planarPoints[2 * lt[2]]};
    int corner = 0;
    double widest = -2;
    for (int c = 0; c < 3; ++c) {
      const double ux = q[(c + 1) % 3][0] - q[c][0], uy = q[(c + 1) % 3][1] - q[c][1];
      const double vx = q[(c + 2) % 3][0] - q[c][0], vy = q[(c + 2) % 3][1] - q[c][1];
      const double cosA = (ux * vx + uy * vy) / (dmath::hypot(ux, uy) * dmath::hypot(vx, vy));
      if (-cosA > widest) widest = -cosA, corner = c;
    }
    for (int k = 0; k < 2; ++k)
      w.requiredPoints.push_back(0.5 * q[corner][k] + 0.25 * (q[(corner + 1) % 3][k] + q[(corner + 2) % 3][k]));
    w.needsMesh = true;
    if (keepBoundary) w.keepBoundary = true;
  }
  // A shared chord is split inside its patch: a vertex at its planar midpoint.
  for (const auto& [t, c] : verdict.chords) {
    PatchWork& w = *patches[triPatch[t]];
    const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
    const double* a = &w.planarPoints[2 * lt[c]];
    const double* b = &w.planarPoints[2 * lt[(c + 1) % 3]];
    w.requiredPoints.insert(w.requiredPoints.end(), {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
    w.needsMesh = true;
    if (keepBoundary) w.keepBoundary = true;
  }
  for (size_t t = 0; t < out.triangleCount(); ++t) {
    if (!exempt.bad(out, t)) continue;
    PatchWork& w = *patches[triPatch[t]];
    const uint32_t* lt = &w.triangles[3 * (t - firstTri[triPatch[t]])];
    double cx = 0, cy = 0, longest = 0;
    for (int c = 0; c < 3; ++c) {
      cx += w.planarPoints[2 * lt[c]] / 3.0;
      cy += w.planarPoints[2 * lt[c] + 1] / 3.0;
      uint32_t a = lt[c], b = lt[(c + 1) % 3];
      longest = std::max(longest, dmath::hypot(w.planarPoints[2 * a] - w.planarPoints[2 * b],
                                             w.planarPoints[2 * a + 1] - w.planarPoints[2 * b + 1]));
    }
    w.spots.push_back({cx, cy, 0.5 * longest});
    w.needsMesh = true;
  }
}

}  // namespace conformesh::pipeline
