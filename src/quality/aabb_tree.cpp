#include "quality/aabb_tree.h"

#include <algorithm>
#include <cmath>

namespace conformesh::quality {

double Box3::diagonal() const {
  if (empty()) return 0.0;
  double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  return std::sqrt(x * x + y * y + z * z);
}

void AabbTree::build(const std::vector<Box3>& boxes) {
  nodes_.clear();
  order_.resize(boxes.size());
  if (boxes.empty()) return;
  std::vector<Vec3> centroid(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    order_[i] = uint32_t(i);
    for (int k = 0; k < 3; ++k) centroid[i][k] = 0.5 * (boxes[i].lo[k] + boxes[i].hi[k]);
  }
  constexpr uint32_t kLeafSize = 4;
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  struct Task {
    uint32_t node, begin, end;
  };
  std::vector<Task> tasks;
  nodes_.push_back({});
  tasks.push_back({0, 0, uint32_t(boxes.size())});
  while (!tasks.empty()) {
    Task t = tasks.back();
    tasks.pop_back();
    Box3 box, cbox;
    for (uint32_t i = t.begin; i < t.end; ++i) {
      box.add(boxes[order_[i]]);
      cbox.add(centroid[order_[i]]);
    }
    nodes_[t.node].box = box;
    uint32_t n = t.end - t.begin;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (cbox.hi[k] - cbox.lo[k] > cbox.hi[axis] - cbox.lo[axis]) axis = k;
    if (n <= kLeafSize || !(cbox.hi[axis] > cbox.lo[axis])) {
      // nth_element leaves each side in an order that differs between standard libraries
      // (libstdc++ natively, libc++ in WASM); sorted leaves make ties in queries resolve alike
      std::sort(order_.begin() + t.begin, order_.begin() + t.end);
      nodes_[t.node].first = t.begin;
      nodes_[t.node].count = n;
      continue;
    }
    uint32_t mid = t.begin + n / 2;
    std::nth_element(order_.begin() + t.begin, order_.begin() + mid, order_.begin() + t.end,
                     [&](uint32_t a, uint32_t b) {
                       if (centroid[a][axis] != centroid[b][axis]) return centroid[a][axis] < centroid[b][axis];
                       return a < b;  // deterministic order for equal keys
                     });
    uint32_t left = uint32_t(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    nodes_[t.node].first = left;
    nodes_[t.node].count = 0;
    tasks.push_back({left, t.begin, mid});
    tasks.push_back({left + 1, mid, t.end});
  }
}

namespace {
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 madd(const Vec3& a, const Vec3& d, double t) { return {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]}; }
}  // namespace

Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = sub(b, a);
  double len2 = dot(ab, ab);
  if (!(len2 > 0)) return a;
  double t = dot(sub(p, a), ab) / len2;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return madd(a, ab, t);
}

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  Vec3 bp = sub(p, b);
  double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double den = d1 - d3;
    return den > 0 ? madd(a, ab, d1 / den) : a;
  }
  Vec3 cp = sub(p, c);
  double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double den = d2 - d6;
    return den > 0 ? madd(a, ac, d2 / den) : a;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double den = (d4 - d3) + (d5 - d6);
    return den > 0 ? madd(b, sub(c, b), (d4 - d3) / den) : b;
  }
  double den = va + vb + vc;
  // Zero (or non-finite) denominator: the triangle is degenerate; use its edges.
  if (!(std::fabs(den) > 0) || !std::isfinite(den)) {
    Vec3 best = closestPointOnSegment(p, a, b);
    for (const Vec3& q : {closestPointOnSegment(p, b, c), closestPointOnSegment(p, c, a)})
      if (distanceSquared(p, q) < distanceSquared(p, best)) best = q;
    return best;
  }
  double v = vb / den, w = vc / den;
  return {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
}

}  // namespace conformesh::quality
