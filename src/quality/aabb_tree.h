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
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "core/vec3.h"

namespace conformesh::quality {

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

//! Morton codes (bits of x, y, z interleaved; Morton 1966) of points on a 2^21 grid of cubic
//! cells over a box: points with nearby codes are near each other. Points outside the box (and
//! NaN) are clamped to its cells.
class MortonGrid {
 public:
  explicit MortonGrid(const Box3& box);
  uint64_t code(const Vec3& p) const;
  //! Sort (code, index) pairs as std::sort does, in linear time for spread codes (a counting
  //! sort on the codes' leading bits, then each bucket; core/bucket_sort.h).
  static void sort(std::vector<std::pair<uint64_t, uint32_t>>& keyed);

 private:
  static constexpr double kCells = 2097151.0;  // 2^21 - 1
  Vec3 lo_;
  double scale_ = 0;
};

//! Result of a closest-primitive query: primitive index (-1 if none within the bound) and the
//! squared distance.
struct ClosestHit {
  int64_t primitive = -1;
  double distanceSquared = std::numeric_limits<double>::infinity();
};

//! How an AabbTree is split. Queries give the same distances on either tree; which of two
//! equidistant primitives a query names, and how fast it is, depend on the tree.
enum class AabbSplit {
  //! Median centroid along the node's longest axis: tight boxes, O(n log n) partitions (~0.12 s
  //! for 193k triangles here).
  Median,
  //! Morton order (Lauterbach et al. 2009, "Fast BVH construction on GPUs", the LBVH): centroids
  //! sorted by their Morton code on a 2^21 grid, each node split where its range's highest
  //! differing code bit flips (at the middle when the codes are equal). About 5× faster to build,
  //! slightly looser boxes.
  Morton
};

class AabbTree {
 public:
  AabbTree() = default;
  //! Build over one box per primitive. O(n log n).
  explicit AabbTree(const std::vector<Box3>& boxes, AabbSplit split = AabbSplit::Median) { build(boxes, split); }
  void build(const std::vector<Box3>& boxes, AabbSplit split = AabbSplit::Median);
  //! The same, box i given by boxOf(i) (called a few times per primitive; no copy is kept).
  void build(size_t count, const std::function<Box3(uint32_t)>& boxOf, AabbSplit split = AabbSplit::Median);

  size_t size() const { return order_.size(); }

  //! Closest primitive to p. `distSq(primitiveIndex, p)` returns the squared distance from p to
  //! that primitive. Only hits strictly closer than `boundSquared` are reported (pass a previous
  //! answer's distance to speed up coherent query sequences; infinity for none).
  //! stopSquared: the search returns at the first primitive found at squared distance <=
  //! stopSquared (a witness that p is that close, not necessarily the closest); when no primitive
  //! is that close the answer is the closest, as without it. Negative (the default): never stops.
  template <class DistSqFn>
  ClosestHit closest(const Vec3& p, DistSqFn&& distSq,
                     double boundSquared = std::numeric_limits<double>::infinity(),
                     double stopSquared = -1.0) const {
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
            if (d <= stopSquared) return best;
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

  //! A primitive within sqrt(stopSquared) of p among the primitives of the subtree `levels`
  //! levels above the leaf that holds primitive `near` (its neighbours in the tree): the first
  //! one found, nearer boxes first; primitive −1 when none of them is that close. For coherent
  //! queries that only need a witness of closeness, not the closest primitive.
  template <class DistSqFn>
  ClosestHit withinNear(const Vec3& p, DistSqFn&& distSq, double stopSquared, uint32_t near, int levels) const {
    ClosestHit none;
    if (near >= leafOf_.size()) return none;
    uint32_t root = leafOf_[near];
    for (int i = 0; i < levels && root != 0; ++i) root = parent_[root];
    uint32_t stack[128];
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (n.box.distanceSquared(p) > stopSquared) continue;
      if (n.count > 0) {
        for (uint32_t i = 0; i < n.count; ++i) {
          uint32_t prim = order_[n.first + i];
          double d = distSq(prim, p);
          if (d <= stopSquared) return {int64_t(prim), d};
        }
        continue;
      }
      uint32_t a = n.first, b = n.first + 1;
      double da = nodes_[a].box.distanceSquared(p), db = nodes_[b].box.distanceSquared(p);
      if (da > db) {
        std::swap(a, b);
        std::swap(da, db);
      }
      if (db <= stopSquared && top < 128) stack[top++] = b;
      if (da <= stopSquared && top < 128) stack[top++] = a;
    }
    return none;
  }

 private:
  static constexpr uint32_t kLeafSize = 4;
  //! Splits [0, n) top-down: split(begin, end) returns where the range divides, `end` for a leaf
  //! (order_[begin, end) then holds its primitives).
  template <class SplitFn>
  void buildTopDown(uint32_t n, SplitFn split);
  void buildMedian(uint32_t n, const std::function<Box3(uint32_t)>& boxOf);
  void buildMorton(uint32_t n, const std::function<Box3(uint32_t)>& boxOf);
  void makeLeaf(uint32_t node, uint32_t begin, uint32_t end);  // order_[begin, end) sorted
  uint32_t addChildren(uint32_t node);                          // two new nodes; the left one's index

  struct Node {
    Box3 box;
    uint32_t first = 0;  // leaf: first index into order_; inner: index of the left child
    uint32_t count = 0;  // leaf: number of primitives (> 0); inner: 0
  };
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;
  std::vector<uint32_t> parent_;  // parent node of each node (the root's: 0)
  std::vector<uint32_t> leafOf_;  // leaf node of each primitive
};

//! Closest point to p on triangle (a, b, c), by Voronoi-region classification (Ericson,
//! "Real-Time Collision Detection", 2005, §5.1.5). Degenerate triangles fall back to the closest
//! of their three edges.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
//! Closest point to p on segment [a, b] (a point when a == b).
Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

inline double distanceSquared(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b;
  return dot(d, d);
}

}  // namespace conformesh::quality
