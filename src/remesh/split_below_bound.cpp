#include "remesh/split_below_bound.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "features/edge_graph.h"

namespace conformesh::optimization {
namespace {

// The 3D angle at p of the triangle (p, q, r), in degrees.
double angleAt(const Vec3& p, const Vec3& q, const Vec3& r) { return features::angleBetween(q - p, r - p) * (180.0 / kPi); }

// `approx`: the optimizer's min angles (minAngleDeg3Approx, within 1e-4° of the exact ones) when
// there is one per triangle: only the triangles it puts near or below the bound are measured.
size_t countBelow(const std::vector<uint32_t>& tri, const std::vector<Vec3>& pos, double bound, const std::vector<double>& approx) {
  const bool screen = approx.size() == tri.size() / 3;
  size_t n = 0;
  for (size_t t = 0; t < tri.size() / 3; ++t)
    if (!screen || !(approx[t] >= bound + 1e-3)) n += minAngleDeg3(pos[tri[3 * t]], pos[tri[3 * t + 1]], pos[tri[3 * t + 2]]) < bound;
  return n;
}

// The patch's whole angle at vertex s: the sum over its triangles.
double wedgeAt(const std::vector<uint32_t>& tri, const std::vector<Vec3>& pos, uint32_t s) {
  double sum = 0;
  for (size_t t = 0; t < tri.size() / 3; ++t)
    for (int c = 0; c < 3; ++c)
      if (tri[3 * t + c] == s) sum += angleAt(pos[s], pos[tri[3 * t + (c + 1) % 3]], pos[tri[3 * t + (c + 2) % 3]]);
  return sum;
}

// The triangle with the directed edge (a, b) and the corner of a in it; false when none (a
// boundary edge seen from the other side).
bool findEdge(const std::vector<uint32_t>& tri, uint32_t a, uint32_t b, size_t& t, int& c) {
  for (t = 0; t < tri.size() / 3; ++t)
    for (c = 0; c < 3; ++c)
      if (tri[3 * t + c] == a && tri[3 * t + (c + 1) % 3] == b) return true;
  return false;
}

// The optimizer's cache (optimize.h) after the split of the edge shared by triangles ta (with the
// directed edge a -> b at its corner ca) and tu (b -> a at cu) at the new vertex m, ta and tu
// rewritten as (a, m, x) and (b, m, d) and (m, b, x), (m, a, d) appended: the adjacency patched
// around them, the new triangles' slots added (their min angles and guard points are recomputed
// by the optimization, every vertex of theirs being active), the stars left stale.
void splitCache(OptimizeCache& c, const std::vector<uint32_t>& tri0, size_t ta, int ca, size_t tu, int cu) {
  constexpr uint32_t none = kNoTriangle;
  const uint32_t nA = uint32_t(tri0.size() / 3), nB = nA + 1;
  const uint32_t bx = c.adjacency[3 * ta + (ca + 1) % 3], xa = c.adjacency[3 * ta + (ca + 2) % 3];
  const uint32_t ad = c.adjacency[3 * tu + (cu + 1) % 3], db = c.adjacency[3 * tu + (cu + 2) % 3];
  c.adjacency.resize(3 * size_t(nB + 1));
  const auto set = [&](size_t t, uint32_t s0, uint32_t s1, uint32_t s2) {
    c.adjacency[3 * t] = s0, c.adjacency[3 * t + 1] = s1, c.adjacency[3 * t + 2] = s2;
  };
  set(ta, nB, nA, xa);                 // (a, m, x)
  set(tu, nA, nB, db);                 // (b, m, d)
  set(nA, uint32_t(tu), bx, uint32_t(ta));  // (m, b, x)
  set(nB, uint32_t(ta), ad, uint32_t(tu));  // (m, a, d)
  const auto repoint = [&](uint32_t t, uint32_t from, uint32_t to) {
    if (t == none) return;
    for (int k = 0; k < 3; ++k)
      if (c.adjacency[3 * size_t(t) + k] == from) c.adjacency[3 * size_t(t) + k] = to;
  };
  repoint(bx, uint32_t(ta), nA);
  repoint(ad, uint32_t(tu), nB);
  c.minAngle.resize(nB + 1, 0.0);
  c.starStart.clear(), c.starTri.clear();
  if (!c.guardHead.empty()) c.guardHead.resize(nB + 1, none), c.guardErr.resize(nB + 1, 0.0);
}

}  // namespace

SplitStats splitBelowBound(std::vector<double>& xy, std::vector<uint32_t>& triangles, std::vector<Vec3>& pos,
                           std::vector<uint8_t>& fixed, const LiftFn& lift, const OptimizeOptions& o,
                           const SurfaceSamples& guard, const SplitOptions& so) {
  SplitStats st;
  const double bound = o.minAngleDeg;
  size_t below = 0;  // triangles below the bound in the patch
  OptimizeOptions local = o;
  local.boundPasses = std::max(o.boundPasses, so.boundPasses);
  // what each optimization leaves for the next (optimize.h): a try would otherwise bucket the
  // guard's points and build the adjacency over the whole patch (ChineseDragon-10kv at 35°: a
  // fifth of the run in the guard's bucketing alone)
  OptimizeCache cache;
  // a pass over the triangles below the bound, again while one keeps a split (a kept split's
  // optimization flips and moves around it: the triangles there are new)
  for (bool again = true; again && !st.capped;) {
    again = false;
    std::vector<uint32_t> todo;
    for (size_t t = 0; t < triangles.size() / 3; ++t)
      if (minAngleDeg3(pos[triangles[3 * t]], pos[triangles[3 * t + 1]], pos[triangles[3 * t + 2]]) < bound)
        todo.push_back(uint32_t(t));
    below = todo.size();
    for (uint32_t t : todo) {
      const uint32_t* v = &triangles[3 * size_t(t)];
      double ang[3];
      for (int c = 0; c < 3; ++c) ang[c] = angleAt(pos[v[c]], pos[v[(c + 1) % 3]], pos[v[(c + 2) % 3]]);
      const int c = int(std::min_element(ang, ang + 3) - ang);
      if (ang[c] >= bound) continue;  // an earlier split's optimization lifted it
      const uint32_t s = v[c], next = v[(c + 1) % 3], prev = v[(c + 2) % 3];
      // three boundary vertices: a strip between curves, or an input corner's wedge, which the
      // refinement leaves as the curves force it
      // (in a patch with inner curves, a chord between two of them may be split: tried below)
      if (fixed[v[0]] && fixed[v[1]] && fixed[v[2]] && o.keptEdges.empty()) continue;
      // an input corner: a boundary vertex with less than the bound in the whole patch
      if (fixed[s] && wedgeAt(triangles, pos, s) < bound) continue;
      // the two edges at the smallest corner, as directed in t
      const uint32_t edges[2][2] = {{s, next}, {prev, s}};
      for (const auto& e : edges) {
        if (st.attempts >= size_t(so.maxAttempts)) {
          st.capped = true;
          break;
        }
        size_t tu;
        int cu;
        if (fixed[e[0]] && fixed[e[1]] && keptEdge(o, e[0], e[1])) continue;  // an inner curve's segment
        if (!findEdge(triangles, e[1], e[0], tu, cu)) continue;  // a boundary edge: never split
        size_t ta;
        int ca;
        findEdge(triangles, e[0], e[1], ta, ca);
        const uint32_t a = e[0], b = e[1], x = triangles[3 * ta + (ca + 2) % 3], d = triangles[3 * tu + (cu + 2) % 3];
        const uint32_t m = uint32_t(xy.size() / 2);
        const double mx = 0.5 * (xy[2 * size_t(a)] + xy[2 * size_t(b)]), my = 0.5 * (xy[2 * size_t(a) + 1] + xy[2 * size_t(b) + 1]);
        ++st.attempts;
        Vec3 P;
        if (!lift(m, mx, my, P)) continue;
        const std::vector<double> xy0 = xy;
        const std::vector<uint32_t> tri0 = triangles;
        const std::vector<Vec3> pos0 = pos;
        const OptimizeCache cache0 = cache;
        xy.insert(xy.end(), {mx, my});
        pos.push_back(P);
        fixed.push_back(0);
        // (a, b, x) -> (a, m, x), (m, b, x); (b, a, d) -> (b, m, d), (m, a, d): counter-clockwise
        // as they were, m on their shared edge
        triangles[3 * ta] = a, triangles[3 * ta + 1] = m, triangles[3 * ta + 2] = x;
        triangles[3 * tu] = b, triangles[3 * tu + 1] = m, triangles[3 * tu + 2] = d;
        triangles.insert(triangles.end(), {m, b, x, m, a, d});
        // the optimization starts at the split's vertices and their neighbours
        std::vector<uint8_t> active(m + 1, 0);
        for (uint32_t q : {a, b, x, d, m}) active[q] = 2;
        for (size_t k = 0; k < triangles.size() / 3; ++k) {
          const uint32_t* w = &triangles[3 * k];
          if (active[w[0]] == 2 || active[w[1]] == 2 || active[w[2]] == 2)
            for (int j = 0; j < 3; ++j) active[w[j]] = std::max<uint8_t>(active[w[j]], 1);
        }
        if (cache.adjacency.size() == tri0.size()) splitCache(cache, tri0, ta, ca, tu, cu);
        const OptimizeStats os = optimizePatch(xy, triangles, pos, fixed, lift, local, active, guard, &cache);
        const size_t now = countBelow(triangles, pos, bound, cache.minAngle);
        if (now < below) {
          below = now;
          ++st.splits;
          st.optimize.moves += os.moves;
          st.optimize.flips += os.flips;
          st.optimize.collapses += os.collapses;
          again = true;
          break;
        }
        xy = xy0;
        triangles = tri0;
        pos = pos0;
        cache = cache0;
        fixed.pop_back();
      }
      if (st.capped) break;
    }
  }
  if (st.capped && below == 0) st.capped = false;
  return st;
}

}  // namespace conformesh::optimization
