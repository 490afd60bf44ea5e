#include "remesh/stitch_defects.h"

#include <algorithm>
#include <tuple>

namespace conformesh {

std::vector<std::array<size_t, 2>> sharedChords(const MeshBuffers& m, const std::vector<uint32_t>& trianglePatch) {
  struct Side { uint32_t a, b, patch; size_t t; int c; };
  std::vector<Side> sides(m.triangles.size());
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t u = m.triangles[3 * t + size_t(c)], w = m.triangles[3 * t + size_t(c + 1) % 3];
      sides[3 * t + size_t(c)] = {std::min(u, w), std::max(u, w), trianglePatch[t], t, c};
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return std::tie(x.a, x.b, x.patch, x.t) < std::tie(y.a, y.b, y.patch, y.t);
  });
  std::vector<std::array<size_t, 2>> out;
  for (size_t i = 0, j; i < sides.size(); i = j) {
    for (j = i; j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b;) ++j;
    if (j - i < 3) continue;
    for (size_t k = i; k + 1 < j; ++k)
      if (sides[k].patch == sides[k + 1].patch && (k == i || sides[k - 1].patch != sides[k].patch))
        out.push_back({sides[k].t, size_t(sides[k].c)});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<size_t> doubledTriangles(const MeshBuffers& m, const std::vector<uint32_t>& trianglePatch) {
  // the triangles' sorted vertex triples in (v0, v1, v2, t) order: a counting sort on v0, then
  // an insertion sort of each (short) bucket on (v1, v2), stable, so t ascending within ties
  const size_t nt = m.triangleCount(), nv = m.vertexCount();
  std::vector<std::array<uint32_t, 3>> sorted(nt);
  std::vector<uint32_t> start(nv + 1, 0);
  std::vector<size_t> patchSize;
  for (size_t t = 0; t < nt; ++t) {
    std::array<uint32_t, 3> v{m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]};
    std::sort(v.begin(), v.end());
    sorted[t] = v;
    ++start[v[0] + 1];
    if (trianglePatch[t] >= patchSize.size()) patchSize.resize(trianglePatch[t] + 1, 0);
    ++patchSize[trianglePatch[t]];
  }
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> order(nt);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < nt; ++t) order[fill[sorted[t][0]]++] = uint32_t(t);
  }
  auto less = [&](uint32_t a, uint32_t b) {
    return sorted[a][1] != sorted[b][1] ? sorted[a][1] < sorted[b][1] : sorted[a][2] < sorted[b][2];
  };
  std::vector<size_t> out;
  for (size_t v = 0; v < nv; ++v) {
    uint32_t* lo = order.data() + start[v];
    uint32_t* hi = order.data() + start[v + 1];
    if (hi - lo > 24) std::stable_sort(lo, hi, less);
    else
      for (uint32_t* i = lo + 1; i < hi; ++i)
        for (uint32_t* j = i; j > lo && less(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
    for (uint32_t* i = lo; i + 1 < hi; ++i) {
      const uint32_t a = i[0], b = i[1];
      if (sorted[a] != sorted[b]) continue;
      out.push_back(patchSize[trianglePatch[a]] >= patchSize[trianglePatch[b]] ? a : b);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace conformesh
