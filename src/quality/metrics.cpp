#include "quality/metrics.h"
#include "core/constants.h"
#include "core/detmath.h"
#include "core/parallel_for.h"
#include "core/triangle_corner.h"
#include "core/union_find.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace conformesh::quality {

namespace {

constexpr double kDeg = 180.0 / kPi;
// surfaceSamples takes the midpoints of edges that bend more than this (and of boundary edges):
// the output's creases and the input's sharp edges, well below the 40° feature angle
constexpr double kCreaseMidpointDeg = 20.0;

inline Vec3 vertex(const MeshBuffers& m, uint32_t i) {
  return vec3At(m.positions, i);
}

//! Angle between u and v in radians, by atan2(|u×v|, u·v): accurate for needles too.
inline double angleBetween(const Vec3& u, const Vec3& v) { return dmath::atan2(norm(cross(u, v)), dot(u, v)); }

bool triangleValid(const MeshBuffers& m, size_t f) {
  size_t n = m.vertexCount();
  const uint32_t* t = &m.triangles[3 * f];
  return t[0] < n && t[1] < n && t[2] < n;
}

//! Undirected edge with the face it came from and the corner opposite to it.
struct EdgeRef {
  uint32_t a, b;  // a < b
  uint32_t face;
  uint8_t corner;  // local index of the opposite corner in `face`
};

//! Every face side as an EdgeRef, ordered by (a, b, face): a counting sort on `a` (O(n)), then a
//! sort inside each vertex's bucket, which holds about its degree of entries.
std::vector<EdgeRef> sortedEdgeRefs(const MeshBuffers& m) {
  const size_t nv = m.vertexCount();
  std::vector<uint32_t> start(nv + 1, 0);
  auto forEachSide = [&](auto&& visit) {
    for (size_t f = 0; f < m.triangleCount(); ++f) {
      if (!triangleValid(m, f)) continue;
      const uint32_t* t = &m.triangles[3 * f];
      for (int k = 0; k < 3; ++k) {
        uint32_t a = t[(k + 1) % 3], b = t[(k + 2) % 3];
        if (a != b) visit(EdgeRef{std::min(a, b), std::max(a, b), uint32_t(f), uint8_t(k)});
      }
    }
  };
  forEachSide([&](const EdgeRef& r) { ++start[r.a + 1]; });
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<EdgeRef> refs(start[nv]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  forEachSide([&](const EdgeRef& r) { refs[fill[r.a]++] = r; });
  // faces arrive in increasing order, so within a bucket ordering by b alone (stably) is enough
  auto byB = [](const EdgeRef& x, const EdgeRef& y) { return x.b < y.b; };
  for (size_t v = 0; v < nv; ++v) {
    EdgeRef* lo = refs.data() + start[v];
    EdgeRef* hi = refs.data() + start[v + 1];
    if (hi - lo <= 24) {
      for (EdgeRef* i = lo + 1; i < hi; ++i)  // insertion sort: stable, fast on short buckets
        for (EdgeRef* j = i; j > lo && byB(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
    } else {
      std::stable_sort(lo, hi, byB);
    }
  }
  return refs;
}

//! Sine and cosine of the angle opposite to edge `r` in its face; false when degenerate.
bool oppositeSinCos(const MeshBuffers& m, const EdgeRef& r, double& sinA, double& cosA) {
  const uint32_t* t = &m.triangles[3 * size_t(r.face)];
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
  const Vec3 o = vertex(m, t[r.corner]);
  const Vec3 u = vertex(m, t[(r.corner + 1) % 3]) - o, v = vertex(m, t[(r.corner + 2) % 3]) - o;
  const double lu = norm(u), lv = norm(v), cr = norm(cross(u, v));
  if (!(cr > 0) || !(lu > 0) || !(lv > 0) || !std::isfinite(cr)) return false;
  sinA = cr / (lu * lv);
  cosA = dot(u, v) / (lu * lv);
  return std::isfinite(sinA) && std::isfinite(cosA);
}

//! Whether the angle opposite to edge `r` is at most 90° (u·v >= 0) with oppositeSinCos sure to
//! succeed (a nonzero cross product, sides far from under- and overflow); false when unsure.
bool oppositeSurelyNotObtuse(const MeshBuffers& m, const EdgeRef& r) {
  const uint32_t* t = &m.triangles[3 * size_t(r.face)];
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
  const Vec3 o = vertex(m, t[r.corner]);
  const Vec3 u = vertex(m, t[(r.corner + 1) % 3]) - o, v = vertex(m, t[(r.corner + 2) % 3]) - o;
  const double uu = dot(u, u), vv = dot(v, v), cc = dot(cross(u, v), cross(u, v));
  return dot(u, v) >= 0 && uu >= 1e-200 && uu <= 1e200 && vv >= 1e-200 && vv <= 1e200 && cc > 0 && cc <= 1e300;
}

Vec3 faceNormal(const MeshBuffers& m, uint32_t f) {
  const uint32_t* t = &m.triangles[3 * size_t(f)];
  Vec3 n = cross(vertex(m, t[1]) - vertex(m, t[0]), vertex(m, t[2]) - vertex(m, t[0]));
  double l = norm(n);
  if (l > 0) n = {n[0] / l, n[1] / l, n[2] / l};
  return n;
}

//! Segments (vertex pairs) of interior manifold edges whose dihedral angle exceeds `angleDeg`,
//! in (a, b) order; with `boundary` also the edges with one face (or more than two).
std::vector<std::pair<uint32_t, uint32_t>> featureEdges(const MeshBuffers& m, double angleDeg, bool boundary = false) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  std::vector<EdgeRef> refs = sortedEdgeRefs(m);
  double cosLimit = dmath::cos(angleDeg / kDeg);
  for (size_t i = 0; i < refs.size();) {
    size_t j = i;
    while (j < refs.size() && refs[j].a == refs[i].a && refs[j].b == refs[i].b) ++j;
    if (j - i != 2) {
      if (boundary) out.emplace_back(refs[i].a, refs[i].b);
    } else {
      Vec3 n0 = faceNormal(m, refs[i].face), n1 = faceNormal(m, refs[i + 1].face);
      // Dihedral (deviation between normals) above the limit <=> cos below the limit. Works for
      // either orientation convention only when the faces are consistently oriented.
      if (dot(n0, n0) > 0 && dot(n1, n1) > 0 && dot(n0, n1) < cosLimit) out.emplace_back(refs[i].a, refs[i].b);
    }
    i = j;
  }
  return out;
}

//! Deterministic uniform double in [0, 1) from a 64-bit generator (splitmix64; Steele et al.
//! 2014). The same bits on every platform, unlike std::uniform_real_distribution.
struct Rng {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
};

//! Max and mean distance from points to a mesh: every point's closest triangle.
void oneSidedWithMean(const std::vector<Vec3>& pts, const TriangleMeshDistance& target, double& maxD,
                      double& meanD) {
  maxD = 0;
  double sum = 0;
  int64_t hint = -1;  // consecutive samples are near each other (same or neighbouring triangles)
  for (const Vec3& p : pts) {
    const ClosestHit hit = target.closest(p, hint);
    hint = hit.primitive;
    double d = std::sqrt(hit.distanceSquared);
    if (!std::isfinite(d)) d = 0;  // target empty: nothing to measure against
    maxD = std::max(maxD, d);
    sum += d;
  }
  meanD = pts.empty() ? 0 : sum / double(pts.size());
}

// The points' indices with their Morton codes over the points' bounding box, in Morton order: the
// order oneSidedMax visits them in (neighbours in a row, the hints stay near).
std::vector<std::pair<uint64_t, uint32_t>> mortonOrder(const std::vector<Vec3>& pts) {
  Box3 box;
  for (const Vec3& p : pts) box.add(p);
  const MortonGrid grid(box);
  std::vector<std::pair<uint64_t, uint32_t>> order(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) order[i] = {grid.code(pts[i]), uint32_t(i)};
  MortonGrid::sort(order);
  return order;
}

// Points per chunk of oneSidedMax: each chunk has its own running max and hint, and chunks of a
// fixed size make the searches the same for every thread count.
constexpr size_t kChunk = 4096;
// Points per chunk of oneSidedMax's first (strided) pass: smaller, so that the pass over the
// 60000 samples of a remesher's input is not one chunk on one thread.
constexpr size_t kFirstChunk = 512;

//! Max distance from points to a mesh, the same value as oneSidedWithMean's, by early breaking
//! (Taha & Hanbury 2015, "An efficient algorithm for calculating the exact Hausdorff distance",
//! IEEE TPAMI 37(11)): a point can raise the running max only if every triangle is farther than
//! it, so its search stops at the first triangle found within the running max (its predecessor's
//! triangle first, then that triangle's neighbours in the tree, then the tree from the root).
//! Each point is either measured exactly (its closest triangle, as without early breaking) or
//! shown to be within the running max, so the max is the same. The points are visited along a
//! Morton curve (each near its predecessor, so the hint is often close enough), and a first pass
//! over every kStride-th of them (spread over the whole surface) sets a running max near the
//! final one, so that most of the others break at once (Taha and Hanbury shuffle the points for
//! this). Both passes run in chunks of consecutive points (kFirstChunk of the first pass's, kChunk)
//! on up to `threads` threads, each chunk from the first pass's max with a running max of its
//! own: the max of the chunks' maxima is the max over every point, whatever order the chunks run
//! in. `order`: mortonOrder(pts).
double oneSidedMax(const std::vector<Vec3>& pts, const std::vector<std::pair<uint64_t, uint32_t>>& order,
                   const TriangleMeshDistance& target, unsigned threads, const std::vector<int64_t>& pointHints = {}) {
  constexpr size_t kStride = 16;
  // a point's own hint (a triangle near a vertex, given by the caller) before its predecessor's
  auto hintOf = [&](uint32_t i, int64_t previous) {
    return i < pointHints.size() && pointHints[i] >= 0 ? pointHints[i] : previous;
  };
  // the points at positions [from, to) of `order` with a step, from a running max (squared)
  auto pass = [&](size_t from, size_t to, size_t step, bool strided, double worst) {
    int64_t hint = -1;
    for (size_t i = from; i < to; i += step) {
      if (!strided && i % kStride == 0) continue;
      const Vec3& p = pts[order[i].second];
      const ClosestHit hit = strided ? target.closest(p, hintOf(order[i].second, hint))
                                     : target.closest(p, hintOf(order[i].second, hint), worst);
      if (hit.primitive < 0) continue;  // no valid triangle in the target: 0, as oneSidedWithMean
      hint = hit.primitive;
      worst = std::max(worst, hit.distanceSquared);
    }
    return worst;
  };
  const size_t n = order.size(), span = kFirstChunk * kStride;
  std::vector<double> firstWorst((n + span - 1) / span, 0.0);
  parallelFor(firstWorst.size(), threads, [&](size_t c) {
    firstWorst[c] = pass(c * span, std::min(n, (c + 1) * span), kStride, true, 0.0);
  });
  double worst = 0;  // squared
  for (double w : firstWorst) worst = std::max(worst, w);
  std::vector<double> chunkWorst((n + kChunk - 1) / kChunk, worst);
  parallelFor(chunkWorst.size(), threads, [&](size_t c) {
    chunkWorst[c] = pass(c * kChunk, std::min(n, (c + 1) * kChunk), 1, false, worst);
  });
  for (double w : chunkWorst) worst = std::max(worst, w);
  return std::sqrt(worst);
}

}  // namespace

bool minMaxAngle(const MeshBuffers& m, size_t f, double& mn, double& mx) {
  if (!triangleValid(m, f)) return false;
  const uint32_t* t = &m.triangles[3 * f];
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
  const Vec3 p[3] = {vertex(m, t[0]), vertex(m, t[1]), vertex(m, t[2])};
  Vec3 u[3], v[3];
  double cr[3], d[3], c[3];
  bool normal = true;  // side lengths far from under- and overflow: the cosines are accurate
  for (int k = 0; k < 3; ++k) {
    u[k] = p[(k + 1) % 3] - p[k];
    v[k] = p[(k + 2) % 3] - p[k];
    cr[k] = norm(cross(u[k], v[k]));
    d[k] = dot(u[k], v[k]);
    const double uu = dot(u[k], u[k]), vv = dot(v[k], v[k]);
    normal = normal && uu >= 1e-200 && uu <= 1e200 && vv >= 1e-200 && vv <= 1e200;
    c[k] = d[k] / (std::sqrt(uu) * std::sqrt(vv));
  }
  if (!(cr[0] > 0)) return false;
  // i0: the largest cosine (smallest angle), i2: the smallest cosine, i1 the other
  int i0 = 0, i2 = 0;
  for (int k = 1; k < 3; ++k) {
    if (c[k] > c[i0]) i0 = k;
    if (c[k] < c[i2]) i2 = k;
  }
  const int i1 = 3 - i0 - i2;
  constexpr double kApart = 1e-9;
  if (normal && i0 != i2 && c[i0] - c[i1] > kApart && c[i1] - c[i2] > kApart && std::isfinite(cr[i1]) && std::isfinite(d[i1])) {
    mn = dmath::atan2(cr[i0], d[i0]);
    mx = dmath::atan2(cr[i2], d[i2]);
    return std::isfinite(mn) && std::isfinite(mx);
  }
  double ang[3];
  for (int k = 0; k < 3; ++k) ang[k] = dmath::atan2(cr[k], d[k]);
  if (!(std::isfinite(ang[0]) && std::isfinite(ang[1]) && std::isfinite(ang[2]))) return false;
  mn = std::min({ang[0], ang[1], ang[2]});
  mx = std::max({ang[0], ang[1], ang[2]});
  return true;
}

AngleStats angleStats(const MeshBuffers& mesh, std::vector<double>* triangleMinAngles) {
  AngleStats s;
  s.triangles = mesh.triangleCount();
  if (triangleMinAngles) triangleMinAngles->assign(s.triangles, std::numeric_limits<double>::quiet_NaN());
  if (s.triangles == 0) return s;
  s.minAngle = 180;
  s.maxAngle = 0;
  double sumMin = 0;
  size_t below20 = 0, below26 = 0, below30 = 0;
  for (size_t f = 0; f < s.triangles; ++f) {
    double mn, mx;
    if (minMaxAngle(mesh, f, mn, mx)) {
      if (triangleMinAngles) (*triangleMinAngles)[f] = mn;
      mn *= kDeg;
      mx *= kDeg;
    } else {
      ++s.degenerateTriangles;
      mn = 0;
      mx = 180;
    }
    s.minAngle = std::min(s.minAngle, mn);
    s.maxAngle = std::max(s.maxAngle, mx);
    sumMin += mn;
    below20 += mn < 20;
    below26 += mn < 26;
    below30 += mn < 30;
    int bin = std::clamp(int(mn / 5.0), 0, 12);
    ++s.minAngleHistogram[bin];
  }
  double n = double(s.triangles);
  s.meanMinAngle = sumMin / n;
  s.pctBelow20 = 100.0 * double(below20) / n;
  s.pctBelow26 = 100.0 * double(below26) / n;
  s.pctBelow30 = 100.0 * double(below30) / n;
  return s;
}

namespace {

EdgeStats edgeStatsOf(const MeshBuffers& mesh, const std::vector<EdgeRef>& refs) {
  EdgeStats s;
  double sum = 0;
  size_t interior = 0, delaunay = 0;
  s.minLength = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < refs.size();) {
    size_t j = i;
    while (j < refs.size() && refs[j].a == refs[i].a && refs[j].b == refs[i].b) ++j;
    double len = norm(vertex(mesh, refs[i].a) - vertex(mesh, refs[i].b));
    ++s.edges;
    sum += len;
    s.minLength = std::min(s.minLength, len);
    s.maxLength = std::max(s.maxLength, len);
    if (j - i == 2) {
      ++interior;
      // Delaunay: the two opposite angles sum to at most pi (within 1e-12), i.e.
      // sin(a0 + a1) = sin a0 cos a1 + cos a0 sin a1 >= -1e-12 (the sum lies in (0, 2 pi)).
      // Two angles of at most 90° pass for sure: both cosines >= 0, so the computed sum is
      // >= -(a few ulp) (most edges of a good mesh; no square root or division for them).
      double s0, c0, s1, c1;
      if ((oppositeSurelyNotObtuse(mesh, refs[i]) && oppositeSurelyNotObtuse(mesh, refs[i + 1])) ||
          (oppositeSinCos(mesh, refs[i], s0, c0) && oppositeSinCos(mesh, refs[i + 1], s1, c1) &&
           s0 * c1 + c0 * s1 >= -1e-12))
        ++delaunay;
    }
    i = j;
  }
  if (s.edges == 0) s.minLength = 0;
  s.meanLength = s.edges ? sum / double(s.edges) : 0;
  s.delaunayFraction = interior ? double(delaunay) / double(interior) : 1.0;
  return s;
}

TopologySummary topologyOf(const MeshBuffers& mesh, const std::vector<EdgeRef>& refs) {
  TopologySummary t;
  size_t nv = mesh.vertexCount();
  std::vector<char> used(nv, 0);
  UnionFind comps(nv);
  for (size_t f = 0; f < mesh.triangleCount(); ++f) {
    if (!triangleValid(mesh, f)) continue;
    ++t.faces;
    const uint32_t* tri = &mesh.triangles[3 * f];
    for (int k = 0; k < 3; ++k) used[tri[k]] = 1;
    comps.unite(tri[0], tri[1]);
    comps.unite(tri[1], tri[2]);
  }
  for (size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++t.vertices;
    if (comps.find(uint32_t(v)) == v) ++t.components;
  }
  UnionFind loops(nv);
  std::vector<char> onBoundary(nv, 0);
  // fans: the corners (3f + k) at a vertex joined across two-triangle edges
  UnionFind fans(mesh.triangles.size());
  const auto distinct = [&](uint32_t f) {
    const uint32_t* tri = &mesh.triangles[3 * size_t(f)];
    return tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0];
  };
  const auto corner = [&](uint32_t f, uint32_t v) { return 3 * f + uint32_t(cornerOf(&mesh.triangles[3 * size_t(f)], v)); };
  for (size_t i = 0; i < refs.size();) {
    size_t j = i;
    while (j < refs.size() && refs[j].a == refs[i].a && refs[j].b == refs[i].b) ++j;
    ++t.edges;
    if (j - i == 1) {
      ++t.boundaryEdges;
      onBoundary[refs[i].a] = onBoundary[refs[i].b] = 1;
      loops.unite(refs[i].a, refs[i].b);
    } else if (j - i > 2) {
      ++t.nonManifoldEdges;
    } else if (distinct(refs[i].face) && distinct(refs[i + 1].face)) {
      fans.unite(corner(refs[i].face, refs[i].a), corner(refs[i + 1].face, refs[i].a));
      fans.unite(corner(refs[i].face, refs[i].b), corner(refs[i + 1].face, refs[i].b));
    }
    i = j;
  }
  for (size_t v = 0; v < nv; ++v)
    if (onBoundary[v] && loops.find(uint32_t(v)) == v) ++t.boundaryLoops;
  std::vector<uint32_t> fanCount(nv, 0);
  for (uint32_t f = 0; f < mesh.triangleCount(); ++f)
    if (triangleValid(mesh, f) && distinct(f))
      for (uint32_t c = 3 * f; c < 3 * f + 3; ++c)
        if (fans.find(c) == c && ++fanCount[mesh.triangles[c]] == 2) ++t.nonManifoldVertices;
  t.euler = (long long)t.vertices - (long long)t.edges + (long long)t.faces;
  if (t.nonManifoldEdges == 0) {
    long long twice = 2 * (long long)t.components - t.euler - (long long)t.boundaryLoops;
    t.genus = twice >= 0 && twice % 2 == 0 ? twice / 2 : -1;
  }
  return t;
}

}  // namespace

EdgeStats edgeStats(const MeshBuffers& mesh) { return edgeStatsOf(mesh, sortedEdgeRefs(mesh)); }

TopologySummary topologySummary(const MeshBuffers& mesh) { return topologyOf(mesh, sortedEdgeRefs(mesh)); }

EdgeTopology edgeStatsAndTopology(const MeshBuffers& mesh) {
  const std::vector<EdgeRef> refs = sortedEdgeRefs(mesh);
  return {edgeStatsOf(mesh, refs), topologyOf(mesh, refs)};
}

Box3 boundingBox(const MeshBuffers& mesh) {
  Box3 box;
  std::vector<char> used(mesh.vertexCount(), 0);
  bool any = false;
  for (size_t f = 0; f < mesh.triangleCount(); ++f) {
    if (!triangleValid(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) used[mesh.triangles[3 * f + k]] = 1;
    any = true;
  }
  for (size_t v = 0; v < mesh.vertexCount(); ++v)
    if (!any || used[v]) box.add(vertex(mesh, uint32_t(v)));
  return box;
}

TriangleMeshDistance::TriangleMeshDistance(const MeshBuffers& mesh, AabbSplit split) : mesh_(mesh) {
  tree_.build(
      mesh.triangleCount(),
      [&mesh](uint32_t f) {
        Box3 box;  // an invalid triangle's stays empty: never closer than anything
        if (triangleValid(mesh, f))
          for (int k = 0; k < 3; ++k) box.add(vertex(mesh, mesh.triangles[3 * size_t(f) + k]));
        return box;
      },
      split);
}

double TriangleMeshDistance::faceDistanceSquared(uint32_t f, const Vec3& q) const {
  if (!triangleValid(mesh_, f)) return std::numeric_limits<double>::infinity();
  const uint32_t* t = &mesh_.triangles[3 * size_t(f)];
  Vec3 c = closestPointOnTriangle(q, vertex(mesh_, t[0]), vertex(mesh_, t[1]), vertex(mesh_, t[2]));
  return distanceSquared(q, c);
}

ClosestHit TriangleMeshDistance::closest(const Vec3& p, int64_t hint, double stopSquared) const {
  auto distSq = [this](uint32_t f, const Vec3& q) { return faceDistanceSquared(f, q); };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (hint < 0 || size_t(hint) >= mesh_.triangleCount()) return tree_.closest(p, distSq, kInf, stopSquared);
  // the hint's distance bounds the search; a triangle strictly closer replaces it, so the
  // distance is the same as without the hint
  const double dh = distSq(uint32_t(hint), p);
  if (!(dh < kInf)) return tree_.closest(p, distSq, kInf, stopSquared);  // NaN or none
  if (dh <= stopSquared) return {hint, dh};
  if (stopSquared >= 0) {
    // a witness among the hint's neighbours in the tree saves the walk from the root
    constexpr int kLevels = 3;  // a subtree of up to 32 triangles (4 per leaf)
    const ClosestHit near = tree_.withinNear(p, distSq, stopSquared, uint32_t(hint), kLevels);
    if (near.primitive >= 0) return near;
  }
  ClosestHit h = tree_.closest(p, distSq, dh, stopSquared);
  if (h.primitive < 0) h = {hint, dh};
  return h;
}

std::vector<Vec3> surfaceSamples(const MeshBuffers& m, size_t count, uint64_t seed) {
  std::vector<Vec3> pts;
  std::vector<char> used(m.vertexCount(), 0);
  std::vector<double> area(m.triangleCount(), 0.0);
  double total = 0;
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    if (!triangleValid(m, f)) continue;
    const uint32_t* t = &m.triangles[3 * f];
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    double a = 0.5 * norm(cross(vertex(m, t[1]) - vertex(m, t[0]), vertex(m, t[2]) - vertex(m, t[0])));
    if (std::isfinite(a)) area[f] = a;
    total += area[f];
  }
  for (size_t v = 0; v < m.vertexCount(); ++v)
    if (used[v]) pts.push_back(vertex(m, uint32_t(v)));
  if (!(total > 0) || count == 0) return pts;
  // the midpoints of the boundary edges and of the creases (a bend above kCreaseMidpointDeg):
  // where a chord of a curved boundary or crease is farthest from the other surface, which area
  // samples rarely hit exactly
  for (const auto& [a, b] : featureEdges(m, kCreaseMidpointDeg, true)) {
    const Vec3 p = vertex(m, a), q = vertex(m, b);
    pts.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])});
  }
  pts.reserve(pts.size() + count + m.triangleCount());
  Rng rng{seed};
  for (size_t f = 0; f < m.triangleCount(); ++f) {
    if (!(area[f] > 0)) continue;
    double expected = double(count) * area[f] / total;
    size_t n = size_t(expected);
    if (rng.uniform() < expected - double(n)) ++n;
    const uint32_t* t = &m.triangles[3 * f];
    Vec3 a = vertex(m, t[0]), b = vertex(m, t[1]), c = vertex(m, t[2]);
    for (size_t s = 0; s < n; ++s) {
      // Uniform point in a triangle (Osada et al. 2002, "Shape distributions", eq. 1).
      double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
      double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
      pts.push_back({wa * a[0] + wb * b[0] + wc * c[0], wa * a[1] + wb * b[1] + wc * c[1],
                     wa * a[2] + wb * b[2] + wc * c[2]});
    }
  }
  return pts;
}

void hausdorffJob(HausdorffWork& w, const MeshBuffers& a, const MeshBuffers& b, const HausdorffOptions& options,
                  size_t job) {
  // the larger mesh's tree first (a remesher's output has about ten times its input's triangles)
  const bool aFirst = a.triangleCount() >= b.triangleCount();
  if (job == 0 || job == 1) {
    if (options.computeMean) return;  // the mean's full searches use median-split trees of their own
    if ((job == 0) == aFirst) w.toA = std::make_unique<TriangleMeshDistance>(a, AabbSplit::Morton);
    else w.toB = std::make_unique<TriangleMeshDistance>(b, AabbSplit::Morton);
  } else if (job == 2) {
    w.samplesA = surfaceSamples(a, options.samplesPerSide, options.seed);
    if (!options.computeMean) w.orderA = mortonOrder(w.samplesA);
  } else if (job == 3) {
    w.samplesB = surfaceSamples(b, options.samplesPerSide, options.seed + 1);
    if (!options.computeMean) w.orderB = mortonOrder(w.samplesB);
  }
}

HausdorffResult hausdorffMeasure(const HausdorffWork& w, const MeshBuffers& a, const MeshBuffers& b,
                                 const HausdorffOptions& options) {
  HausdorffResult r;
  r.diagonal = boundingBox(b).diagonal();
  const std::vector<Vec3>&sa = w.samplesA, &sb = w.samplesB;
  r.samplesA = sa.size();
  r.samplesB = sb.size();
  if (options.computeMean) {
    oneSidedWithMean(sa, TriangleMeshDistance(b), r.aToB, r.meanAToB);
    oneSidedWithMean(sb, TriangleMeshDistance(a), r.bToA, r.meanBToA);
  } else {
    // the hints of A's vertex samples (the first samples, in vertex order)
    std::vector<int64_t> hintsA;
    const std::vector<uint32_t>* near = options.nearTriangleOfVertexA;
    if (near && near->size() == a.vertexCount()) {
      std::vector<char> used(a.vertexCount(), 0);
      for (size_t f = 0; f < a.triangleCount(); ++f)
        if (triangleValid(a, f))
          for (int k = 0; k < 3; ++k) used[a.triangles[3 * f + k]] = 1;
      for (size_t v = 0; v < a.vertexCount(); ++v)
        if (used[v]) hintsA.push_back((*near)[v] < b.triangleCount() ? int64_t((*near)[v]) : -1);
    }
    r.aToB = oneSidedMax(sa, w.orderA, *w.toB, options.threads, hintsA);
    r.bToA = oneSidedMax(sb, w.orderB, *w.toA, options.threads);
    r.meanAToB = r.meanBToA = -1;
  }
  r.hausdorff = std::max(r.aToB, r.bToA);
  r.relative = r.diagonal > 0 ? r.hausdorff / r.diagonal : 0;
  return r;
}

HausdorffResult hausdorffDistance(const MeshBuffers& a, const MeshBuffers& b, const HausdorffOptions& options) {
  HausdorffWork w;
  parallelFor(HausdorffWork::kJobs, options.threads, [&](size_t job) { hausdorffJob(w, a, b, options, job); });
  return hausdorffMeasure(w, a, b, options);
}

FeatureResult featurePreservation(const MeshBuffers& output, const MeshBuffers& reference,
                                  const FeatureOptions& options) {
  FeatureResult r;
  auto refEdges = featureEdges(reference, options.featureAngle);
  auto outEdges = featureEdges(output, options.outputFeatureAngle);
  r.referenceFeatureEdges = refEdges.size();
  r.outputFeatureEdges = outEdges.size();
  double tol = options.tolerance > 0 ? options.tolerance : 1e-4 * boundingBox(reference).diagonal();
  std::vector<Box3> boxes(outEdges.size());
  for (size_t i = 0; i < outEdges.size(); ++i) {
    boxes[i].add(vertex(output, outEdges[i].first));
    boxes[i].add(vertex(output, outEdges[i].second));
  }
  AabbTree tree(boxes);
  int k = std::max(1, options.samplesPerEdge);
  for (const auto& e : refEdges) {
    Vec3 p = vertex(reference, e.first), q = vertex(reference, e.second);
    for (int s = 0; s < k; ++s) {
      double t = (s + 0.5) / k;
      Vec3 x = {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
      ClosestHit hit = tree.closest(x, [&](uint32_t i, const Vec3& y) {
        return distanceSquared(y, closestPointOnSegment(y, vertex(output, outEdges[i].first),
                                                        vertex(output, outEdges[i].second)));
      });
      double d = std::sqrt(hit.distanceSquared);
      ++r.samples;
      if (d <= tol) ++r.kept;
      r.maxDistance = std::max(r.maxDistance, d);  // infinity when the output has no feature edge
    }
  }
  r.fractionKept = r.samples ? double(r.kept) / double(r.samples) : 1.0;
  return r;
}

}  // namespace conformesh::quality
