#include "features/patch_width.h"

#include <cmath>
#include <limits>

#include "quality/aabb_tree.h"

namespace conformesh::features {

namespace {

// |cos| of the angle between a crossing and an edge's tangent above which the edge is not
// crossed but followed: 60° off the normal
constexpr double kAcrossCos = 0.5;

}  // namespace

std::vector<std::array<double, 2>> patchWidths(const EdgeGraph& g, const Segmentation& seg, double maxDistance) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 2>> width(g.edgeCount(), {kInf, kInf});
  // boundary edges (edge, side) of each patch: its face on that side is in the patch, the other
  // side is another patch or nothing
  const size_t patchCount = seg.patches.size();
  std::vector<std::vector<std::pair<uint32_t, int>>> border(patchCount);
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    const auto& ef = g.edgeFaces[e];
    const uint32_t p0 = seg.facePatch[ef[0]], p1 = ef[1] == kNone ? kNone : seg.facePatch[ef[1]];
    if (p0 == p1 && seg.isInnerEdge(e)) {
      // an inner curve: a constraint inside its patch, sampled as a border is, on both sides
      border[p0].push_back({e, 0});
      border[p0].push_back({e, 1});
      continue;
    }
    if (p0 == p1) continue;
    border[p0].push_back({e, 0});
    if (p1 != kNone) border[p1].push_back({e, 1});
  }
  const double bound = maxDistance * maxDistance;
  for (const auto& edges : border) {
    if (edges.size() < 3) continue;
    quality::AabbTree tree;
    tree.build(edges.size(), [&](uint32_t i) {
      quality::Box3 b;
      for (uint32_t v : g.edgeVerts[edges[i].first]) b.add(g.positions[v]);
      return b;
    });
    for (const auto& edgeSide : edges) {
      const uint32_t e = edgeSide.first;  // not a structured binding: lambdas capture it (C++17)
      const int side = edgeSide.second;
      const auto& ev = g.edgeVerts[e];
      const Vec3 a = g.positions[ev[0]], b = g.positions[ev[1]];
      const double len = norm(b - a);
      if (len == 0) continue;
      const Vec3 m = (a + b) * 0.5, te = (b - a) * (1.0 / len);
      // on an inner curve, only what lies on this side: towards the side's face from the edge
      const bool inner = seg.isInnerEdge(e);
      Vec3 toFace{};
      if (inner) {
        const auto& fv = g.faces[g.edgeFaces[e][side]];
        const uint32_t o = fv[0] != ev[0] && fv[0] != ev[1] ? fv[0] : fv[1] != ev[0] && fv[1] != ev[1] ? fv[1] : fv[2];
        toFace = g.positions[o] - m;
        toFace = toFace - te * dot(toFace, te);
      }
      const quality::ClosestHit hit = tree.closest(m, [&](uint32_t i, const Vec3& p) {
        const uint32_t f = edges[i].first;
        const auto& fv = g.edgeVerts[f];
        if (f == e) return kInf;
        const Vec3 c = g.positions[fv[0]], d = g.positions[fv[1]];
        const double lf = norm(d - c);
        const Vec3 y = quality::closestPointOnSegment(p, c, d), across = y - p;
        const double dist = norm(across);
        if (lf == 0 || dist == 0) return kInf;
        if (inner && !(dot(across, toFace) > 0)) return kInf;
        if (std::abs(dot(across, te)) > kAcrossCos * dist) return kInf;
        if (std::abs(dot(across, d - c)) > kAcrossCos * dist * lf) return kInf;
        return dist * dist;
      }, bound);
      if (hit.primitive >= 0) width[e][side] = std::sqrt(hit.distanceSquared);
    }
  }
  return width;
}

PatchExtents patchExtents(const EdgeGraph& g, const Segmentation& seg) {
  PatchExtents x;
  x.area.assign(seg.patches.size(), 0.0);
  x.perimeter.assign(seg.patches.size(), 0.0);
  for (uint32_t f = 0; f < g.faceCount; ++f) x.area[seg.facePatch[f]] += g.faceArea(f);
  for (uint32_t e = 0; e < g.edgeCount(); ++e) {
    const uint32_t f0 = g.edgeFaces[e][0], f1 = g.edgeFaces[e][1];
    const uint32_t p0 = seg.facePatch[f0], p1 = f1 == kNone ? kNone : seg.facePatch[f1];
    if (p0 == p1) continue;  // inside a patch (a slit counts for nothing)
    x.perimeter[p0] += g.edgeLength(e);
    if (p1 != kNone) x.perimeter[p1] += g.edgeLength(e);
  }
  return x;
}

}  // namespace conformesh::features
