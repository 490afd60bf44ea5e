#include "features/merge_small_patches.h"

#include <algorithm>
#include <vector>

#include "features/patch_mesh.h"

namespace conformesh::features {

uint32_t mergeSmallPatches(const EdgeGraph& g, Segmentation& seg, double minArea) {
  if (!(minArea > 0)) return 0;
  uint32_t merges = 0;
  // each merge removes a patch: at most as many rounds as patches (a hard cap all the same)
  for (size_t round = 0, cap = seg.patches.size(); round <= cap; ++round) {
    std::vector<double> area(seg.patches.size(), 0.0);
    for (size_t p = 0; p < seg.patches.size(); ++p)
      for (uint32_t f : seg.patches[p]) area[p] += g.faceArea(f);
    struct Candidate {
      double area, length;
      uint32_t curve;
    };
    std::vector<Candidate> cands;
    for (uint32_t c = 0; c < seg.curves.size(); ++c) {
      const Curve& cv = seg.curves[c];
      if (cv.kind != EdgeKind::Cut || cv.patches[0] == kNone || cv.patches[1] == kNone || cv.patches[0] == cv.patches[1]) continue;
      const double a = std::min(area[cv.patches[0]], area[cv.patches[1]]);
      if (a < minArea) cands.push_back({a, cv.length, c});
    }
    // the smallest patch first, through its longest cut; the curve id breaks ties (deterministic)
    std::sort(cands.begin(), cands.end(), [](const Candidate& x, const Candidate& y) {
      if (x.area != y.area) return x.area < y.area;
      if (x.length != y.length) return x.length > y.length;
      return x.curve < y.curve;
    });
    bool merged = false;
    std::vector<uint8_t> mask = seg.curveMask();
    for (const Candidate& cand : cands) {
      // the two patches together, cut open along every curve but this one: a disk?
      const Curve& cv = seg.curves[cand.curve];
      std::vector<uint32_t> faces = seg.patches[cv.patches[0]];
      faces.insert(faces.end(), seg.patches[cv.patches[1]].begin(), seg.patches[cv.patches[1]].end());
      for (uint32_t e : cv.edges) mask[e] = 0;
      const bool disk = extractPatch(g, mask, faces, false).isDisk();
      for (uint32_t e : cv.edges) mask[e] = 1;
      if (!disk) continue;
      for (uint32_t e : cv.edges) seg.edgeKind[e] = EdgeKind::None;
      seg.cutEdgeCount -= uint32_t(cv.edges.size());
      rebuildCurves(g, seg);
      ++merges;
      merged = true;
      break;
    }
    if (!merged) break;
  }
  return merges;
}

}  // namespace conformesh::features
