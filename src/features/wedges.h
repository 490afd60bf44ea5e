// conformesh — the wedges at a vertex between curve edges (internal to src/features): what the
// cut repairs and the exempt corners measure.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/constants.h"
#include "features/edge_graph.h"

namespace conformesh::features {

// A cut meeting a curve at a wedge narrower than this makes a corner no mesh can fix (cuts are
// ours, not features, so such a corner is not exempt); straightenCutEars and the walks of
// extendDanglingCurves avoid them.
constexpr double kNarrowCutWedge = 45.0 * kPi / 180.0;

struct WedgeScratch {
  std::vector<uint32_t> star, parent;
  std::vector<double> sum;
};

// The root of star face i's wedge (after groupWedges).
inline uint32_t wedgeRoot(WedgeScratch& w, uint32_t i) {
  while (w.parent[i] != i) i = w.parent[i] = w.parent[w.parent[i]];
  return i;
}

// The wedges at v between edges for which separates(e) holds (the open boundary always
// separates): the faces of v's star (w.star, sorted) joined across the other edges (union-find,
// wedgeRoot), and each wedge's angle at v, the sum of its faces' angles there, at its root
// (w.sum). False, with w unset, when no such edge touches v.
template <class Separates>
inline bool groupWedges(const EdgeGraph& g, uint32_t v, const Separates& separates, WedgeScratch& w) {
  bool touched = false;
  w.star.clear();
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (separates(e) || g.isBoundary(e)) touched = true;
    for (uint32_t f : g.edgeFaces[e])
      if (f != kNone) w.star.push_back(f);
  }
  if (!touched) return false;
  std::sort(w.star.begin(), w.star.end());
  w.star.erase(std::unique(w.star.begin(), w.star.end()), w.star.end());
  w.parent.resize(w.star.size());
  for (uint32_t i = 0; i < w.parent.size(); ++i) w.parent[i] = i;
  auto slot = [&](uint32_t f) { return uint32_t(std::lower_bound(w.star.begin(), w.star.end(), f) - w.star.begin()); };
  for (uint32_t k = g.vertexEdgeStart[v]; k < g.vertexEdgeStart[v + 1]; ++k) {
    const uint32_t e = g.vertexEdgeIds[k];
    if (separates(e) || g.isBoundary(e)) continue;
    w.parent[wedgeRoot(w, slot(g.edgeFaces[e][0]))] = wedgeRoot(w, slot(g.edgeFaces[e][1]));
  }
  w.sum.assign(w.star.size(), 0.0);
  for (uint32_t i = 0; i < w.star.size(); ++i) {
    const auto& fv = g.faces[w.star[i]];
    for (int c = 0; c < 3; ++c)
      if (fv[c] == v) w.sum[wedgeRoot(w, i)] += g.cornerAngle(w.star[i], c);
  }
  return true;
}

// The smallest wedge at v between edges for which separates(e) holds (groupWedges). 2π when no
// such edge touches v; the full angle sum at v when one does.
template <class Separates>
inline double smallestWedge(const EdgeGraph& g, uint32_t v, const Separates& separates, WedgeScratch& w) {
  if (!groupWedges(g, v, separates, w)) return 2 * kPi;
  double m = 2 * kPi;
  for (uint32_t i = 0; i < w.star.size(); ++i)
    if (wedgeRoot(w, i) == i) m = std::min(m, w.sum[i]);
  return m;
}

}  // namespace conformesh::features
