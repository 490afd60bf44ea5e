#include "features/merge_cut_patches.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include "core/union_find.h"
#include "features/patch_mesh.h"
#include "features/patch_width.h"

namespace conformesh::features {

uint32_t mergeCutPatches(const EdgeGraph& g, Segmentation& seg, double maxWidth, const std::vector<uint32_t>& region,
                         const std::vector<uint8_t>& keep, bool pairs, size_t maxFaces) {
  const uint32_t P = uint32_t(seg.patches.size());
  if (P < 2 || !(maxWidth > 0)) return 0;
  UnionFind groups(P);
  std::vector<std::vector<uint32_t>> faces = seg.patches;  // per group root
  PatchExtents extents = patchExtents(g, seg);  // per group root
  std::vector<double>& area = extents.area;
  std::vector<double>& perimeter = extents.perimeter;
  const auto narrow = [&](uint32_t a) { return 2 * area[a] < maxWidth * perimeter[a]; };
  std::vector<uint32_t> order(P);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return 2 * area[a] * perimeter[b] < 2 * area[b] * perimeter[a];  // narrower first
  });
  // the patches narrow to begin with; a wider one that a join makes narrower is not tried
  order.resize(std::count_if(order.begin(), order.end(), narrow));
  std::vector<uint8_t> inRegion(P, region.empty() ? 1 : 0);
  for (const uint32_t f : region) inRegion[seg.facePatch[f]] = 1;
  order.erase(std::remove_if(order.begin(), order.end(), [&](uint32_t p) { return !inRegion[p]; }), order.end());
  std::vector<uint8_t> mask = seg.curveMask();
  uint32_t joins = 0;
  size_t joinedFaces = 0;  // in the joined patches (pairs)
  std::vector<std::pair<uint32_t, uint32_t>> cuts;  // (neighbour group, cut edge) around a group
  std::vector<std::pair<size_t, size_t>> runs;      // [begin, end) of each neighbour's cut edges
  for (uint32_t p : order) {
    if (groups.find(p) != p || !narrow(p)) continue;  // joined into another, or grown past the width
    if (pairs && faces[p].size() != seg.patches[p].size()) continue;  // joined already
    cuts.clear();
    for (uint32_t f : faces[p])
      for (uint32_t e : g.faceEdges[f]) {
        if (seg.edgeKind[e] != EdgeKind::Cut) continue;
        const uint32_t across = g.edgeFaces[e][0] == f ? g.edgeFaces[e][1] : g.edgeFaces[e][0];  // a cut edge has two faces
        const uint32_t b = groups.find(seg.facePatch[across]);
        if (b != p && inRegion[b] && (!pairs || faces[b].size() == seg.patches[b].size())) cuts.push_back({b, e});
      }
    std::sort(cuts.begin(), cuts.end());
    runs.clear();
    for (size_t i = 0; i < cuts.size();) {
      size_t j = i;
      while (j < cuts.size() && cuts[j].first == cuts[i].first) ++j;
      runs.push_back({i, j});
      i = j;
    }
    // most shared cut edges first, the smaller group id on ties (deterministic)
    std::stable_sort(runs.begin(), runs.end(), [](const auto& x, const auto& y) { return x.second - x.first > y.second - y.first; });
    for (const auto& [begin, end] : runs) {
      const uint32_t b = cuts[begin].first;
      if (pairs && faces[p].size() + faces[b].size() > maxFaces - joinedFaces) continue;
      if (!keep.empty() && std::any_of(cuts.begin() + long(begin), cuts.begin() + long(end), [&](const auto& c) { return keep[c.second] != 0; }))
        continue;
      double between = 0;  // length of the shared cut edges
      for (size_t k = begin; k < end; ++k) mask[cuts[k].second] = 0, between += g.edgeLength(cuts[k].second);
      std::vector<uint32_t> joined = faces[p];
      joined.insert(joined.end(), faces[b].begin(), faces[b].end());
      if (!isDiskRegion(g, mask, joined)) {
        for (size_t k = begin; k < end; ++k) mask[cuts[k].second] = 1;
        continue;
      }
      for (size_t k = begin; k < end; ++k) {
        seg.edgeKind[cuts[k].second] = EdgeKind::None;
        --seg.cutEdgeCount;
      }
      joinedFaces += faces[p].size() + faces[b].size();
      groups.unite(p, b);
      const uint32_t root = groups.find(p), gone = root == p ? b : p;
      faces[root] = std::move(joined);
      std::vector<uint32_t>().swap(faces[gone]);
      area[root] = area[p] + area[b];
      perimeter[root] = perimeter[p] + perimeter[b] - 2 * between;
      ++joins;
      break;
    }
  }
  return joins;
}

}  // namespace conformesh::features
