#include "features/merge_cut_patches.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include "core/union_find.h"
#include "features/patch_mesh.h"

namespace conformesh::features {

uint32_t mergeCutPatches(const EdgeGraph& g, Segmentation& seg, double maxWidth) {
  const uint32_t P = uint32_t(seg.patches.size());
  if (P < 2 || !(maxWidth > 0)) return 0;
  UnionFind groups(P);
  std::vector<std::vector<uint32_t>> faces = seg.patches;  // per group root
  // the face across edge e from face f (kNone on the boundary)
  const auto across = [&](uint32_t e, uint32_t f) { return g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0]; };
  // twice the area over the perimeter of group a: the width of a strip
  const auto width = [&](uint32_t a) {
    double area = 0, perimeter = 0;
    for (uint32_t f : faces[a]) {
      area += g.faceArea(f);
      for (uint32_t e : g.faceEdges[f]) {
        const uint32_t other = across(e, f);
        if (other == kNone || groups.find(seg.facePatch[other]) != a) perimeter += g.edgeLength(e);
      }
    }
    return perimeter > 0 ? 2 * area / perimeter : INFINITY;
  };
  std::vector<double> w0(P);
  for (uint32_t p = 0; p < P; ++p) w0[p] = width(p);
  std::vector<uint32_t> order(P);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return w0[a] < w0[b]; });
  std::vector<uint8_t> mask = seg.curveMask();
  uint32_t joins = 0;
  std::vector<std::pair<uint32_t, uint32_t>> shared;  // (neighbour group, cut edges shared)
  std::vector<uint32_t> between;
  for (uint32_t p : order) {
    if (!(w0[p] < maxWidth)) break;
    const uint32_t a = groups.find(p);
    if (a != p || !(width(a) < maxWidth)) continue;  // joined into another, or grown past the width
    shared.clear();
    for (uint32_t f : faces[a])
      for (uint32_t e : g.faceEdges[f]) {
        if (seg.edgeKind[e] != EdgeKind::Cut) continue;
        const uint32_t b = groups.find(seg.facePatch[across(e, f)]);  // a cut edge has two faces
        if (b == a) continue;
        auto it = std::find_if(shared.begin(), shared.end(), [b](const auto& s) { return s.first == b; });
        if (it == shared.end()) shared.push_back({b, 1});
        else ++it->second;
      }
    // most shared cut edges first, the smaller group id on ties (deterministic)
    std::sort(shared.begin(), shared.end(), [](const auto& x, const auto& y) {
      return x.second != y.second ? x.second > y.second : x.first < y.first;
    });
    for (const auto& [b, count] : shared) {
      between.clear();
      for (uint32_t f : faces[a])
        for (uint32_t e : g.faceEdges[f])
          if (seg.edgeKind[e] == EdgeKind::Cut && groups.find(seg.facePatch[across(e, f)]) == b) between.push_back(e);
      for (uint32_t e : between) mask[e] = 0;
      std::vector<uint32_t> joined = faces[a];
      joined.insert(joined.end(), faces[b].begin(), faces[b].end());
      if (!extractPatch(g, mask, joined, true).isDisk()) {
        for (uint32_t e : between) mask[e] = 1;
        continue;
      }
      for (uint32_t e : between) {
        seg.edgeKind[e] = EdgeKind::None;
        --seg.cutEdgeCount;
      }
      groups.unite(a, b);
      const uint32_t root = groups.find(a);
      std::vector<uint32_t>().swap(faces[root == a ? b : a]);
      faces[root] = std::move(joined);
      ++joins;
      break;
    }
  }
  return joins;
}

}  // namespace conformesh::features
