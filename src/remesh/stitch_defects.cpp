#include "remesh/stitch_defects.h"

#include <algorithm>
#include <utility>

namespace conformesh {

std::vector<std::array<size_t, 2>> sharedChords(const MeshBuffers& m, const std::vector<uint32_t>& trianglePatch) {
  // the triangle sides (3t + c) bucketed by their smaller vertex (a counting sort, so t ascending
  // in a bucket), each short bucket then sorted stably on (larger vertex, patch): linear, as it
  // runs on every certificate round of outputs of millions of triangles
  const size_t ns = m.triangles.size(), nv = m.vertexCount();
  auto lo = [&](size_t s) { return std::min(m.triangles[s], m.triangles[s - s % 3 + (s + 1) % 3]); };
  auto hi = [&](size_t s) { return std::max(m.triangles[s], m.triangles[s - s % 3 + (s + 1) % 3]); };
  std::vector<uint32_t> start(nv + 1, 0), order(ns);
  for (size_t s = 0; s < ns; ++s) ++start[lo(s) + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t s = 0; s < ns; ++s) order[fill[lo(s)]++] = uint32_t(s);
  }
  auto less = [&](uint32_t x, uint32_t y) {
    return std::make_pair(hi(x), trianglePatch[x / 3]) < std::make_pair(hi(y), trianglePatch[y / 3]);
  };
  std::vector<std::array<size_t, 2>> out;
  for (size_t v = 0; v < nv; ++v) {
    uint32_t* b = order.data() + start[v];
    uint32_t* e = order.data() + start[v + 1];
    std::stable_sort(b, e, less);
    for (uint32_t *i = b, *j; i < e; i = j) {
      for (j = i; j < e && hi(*j) == hi(*i);) ++j;
      if (j - i < 3) continue;  // a manifold edge, or a boundary one
      for (uint32_t* k = i; k + 1 < j; ++k)
        if (trianglePatch[k[0] / 3] == trianglePatch[k[1] / 3] && (k == i || trianglePatch[k[-1] / 3] != trianglePatch[k[0] / 3]))
          out.push_back({k[0] / 3, k[0] % 3});
    }
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
