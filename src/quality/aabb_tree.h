// conformesh — axis-aligned bounding-box tree for closest-primitive queries in 3D.
//
// A static binary tree over boxes (one per primitive: triangle, segment, ...), split at the
// median centroid along the box's longest axis. Queries are branch-and-bound: a node is visited
// only when its box is closer than the best distance found so far, nearer child first. The
// primitive test is supplied by the caller, so the same tree serves triangles and segments.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace conformesh::quality {

using Vec3 = std::array<double, 3>;

struct Box3 {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      if (p[k] < lo[k]) lo[k] = p[k];
      if (p[k] > hi[k]) hi[k] = p[k];
    }
  }
  void add(const Box3& b) {
    add(b.lo);
    add(b.hi);
  }
  bool empty() const { return lo[0] > hi[0]; }
  //! Squared distance from p to the box (0 inside).
  double distanceSquared(const Vec3& p) const {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      double e = p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0.0);
      d += e * e;
    }
    return d;
  }
  double diagonal() const;
};

//! Result of a closest-primitive query: primitive index (-1 if none within the bound) and the
//! squared distance.
struct ClosestHit {
  int64_t primitive = -1;
  double distanceSquared = std::numeric_limits<double>::infinity();
};

class AabbTree {
 public:
  AabbTree() = default;
  //! Build over one box per primitive. O(n log n).
  explicit AabbTree(const std::vector<Box3>& boxes) { build(boxes); }
  void build(const std::vector<Box3>& boxes);

  size_t size() const { return order_.size(); }

  //! Closest primitive to p. `distSq(primitiveIndex, p)` returns the squared distance from p to
  //! that primitive. Only hits strictly closer than `boundSquared` are reported (pass a previous
  //! answer's distance to speed up coherent query sequences; infinity for none).
  template <class DistSqFn>
  ClosestHit closest(const Vec3& p, DistSqFn&& distSq,
                     double boundSquared = std::numeric_limits<double>::infinity()) const {
    ClosestHit best;
    best.distanceSquared = boundSquared;
    if (nodes_.empty()) return best;
    // Explicit stack; depth is bounded by the tree height (<= 64 for any realistic size).
    uint32_t stack[128];
    int top = 0;
    if (nodes_[0].box.distanceSquared(p) >= best.distanceSquared) return best;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (n.box.distanceSquared(p) >= best.distanceSquared) continue;
      if (n.count > 0) {
        for (uint32_t i = 0; i < n.count; ++i) {
          uint32_t prim = order_[n.first + i];
          double d = distSq(prim, p);
          if (d < best.distanceSquared) {
            best.distanceSquared = d;
            best.primitive = prim;
          }
        }
        continue;
      }
      uint32_t a = n.first, b = n.first + 1;  // children are stored next to each other
      double da = nodes_[a].box.distanceSquared(p), db = nodes_[b].box.distanceSquared(p);
      if (da > db) {
        std::swap(a, b);
        std::swap(da, db);
      }
      // Push the farther child first so the nearer one is popped next.
      if (db < best.distanceSquared && top < 128) stack[top++] = b;
      if (da < best.distanceSquared && top < 128) stack[top++] = a;
    }
    return best;
  }

 private:
  struct Node {
    Box3 box;
    uint32_t first = 0;  // leaf: first index into order_; inner: index of the left child
    uint32_t count = 0;  // leaf: number of primitives (> 0); inner: 0
  };
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;
};

//! Closest point to p on triangle (a, b, c), by Voronoi-region classification (Ericson,
//! "Real-Time Collision Detection", 2005, §5.1.5). Degenerate triangles fall back to the closest
//! of their three edges.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
//! Closest point to p on segment [a, b] (a point when a == b).
Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

inline double distanceSquared(const Vec3& a, const Vec3& b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

}  // namespace conformesh::quality
