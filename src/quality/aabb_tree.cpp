#include "quality/aabb_tree.h"

#include "core/bucket_sort.h"

#include <algorithm>
#include <cmath>

namespace conformesh::quality {

MortonGrid::MortonGrid(const Box3& box) : lo_(box.lo) {
  double extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, box.hi[k] - box.lo[k]);
  scale_ = extent > 0 && std::isfinite(extent) ? kCells / extent : 0.0;
}

uint64_t MortonGrid::code(const Vec3& p) const {
  auto spread = [](uint64_t x) {  // the 21 bits of x to every third bit
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
  };
  uint64_t c = 0;
  for (int k = 0; k < 3; ++k) {
    const double q = (p[k] - lo_[k]) * scale_;
    const uint64_t cell = q > 0 ? uint64_t(std::min(q, kCells)) : 0;  // NaN and below: 0
    c |= spread(cell) << k;
  }
  return c;
}

void MortonGrid::sort(std::vector<std::pair<uint64_t, uint32_t>>& keyed) {
  int bits = 1;  // about one bucket per pair
  while (bits < 24 && (size_t(1) << bits) < keyed.size()) ++bits;
  bucketSort(keyed, size_t(1) << bits, [bits](const std::pair<uint64_t, uint32_t>& e) { return e.first >> (63 - bits); },
             [](const std::pair<uint64_t, uint32_t>& x, const std::pair<uint64_t, uint32_t>& y) { return x < y; });
}

double Box3::diagonal() const {
  if (empty()) return 0.0;
  double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  return std::sqrt(x * x + y * y + z * z);
}

namespace {
Vec3 centroidOf(const Box3& b) {
  return {0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2])};
}
}  // namespace

void AabbTree::build(const std::vector<Box3>& boxes, AabbSplit split) {
  build(boxes.size(), [&boxes](uint32_t i) { return boxes[i]; }, split);
}

void AabbTree::build(size_t count, const std::function<Box3(uint32_t)>& boxOf, AabbSplit split) {
  nodes_.clear();
  order_.resize(count);
  parent_.clear();
  leafOf_.assign(count, 0);
  if (count == 0) return;
  if (split == AabbSplit::Morton)
    buildMorton(uint32_t(count), boxOf);
  else
    buildMedian(uint32_t(count), boxOf);
  // children come after their parent: a reverse sweep unites boxes bottom-up (min and max are
  // exact, so each box equals the union of its primitives' boxes)
  parent_.assign(nodes_.size(), 0);
  for (size_t i = nodes_.size(); i-- > 0;) {
    Node& nd = nodes_[i];
    nd.box = Box3{};
    if (nd.count > 0) {
      for (uint32_t j = 0; j < nd.count; ++j) {
        nd.box.add(boxOf(order_[nd.first + j]));
        leafOf_[order_[nd.first + j]] = uint32_t(i);
      }
    } else {
      nd.box.add(nodes_[nd.first].box);
      nd.box.add(nodes_[nd.first + 1].box);
      parent_[nd.first] = parent_[nd.first + 1] = uint32_t(i);
    }
  }
}

void AabbTree::makeLeaf(uint32_t node, uint32_t begin, uint32_t end) {
  // splits leave each side in an order that differs between standard libraries (libstdc++
  // natively, libc++ in WASM); sorted leaves make ties in queries resolve alike
  std::sort(order_.begin() + begin, order_.begin() + end);
  nodes_[node].first = begin;
  nodes_[node].count = end - begin;
}

uint32_t AabbTree::addChildren(uint32_t node) {
  const uint32_t left = uint32_t(nodes_.size());
  nodes_.push_back({});
  nodes_.push_back({});
  nodes_[node].first = left;
  nodes_[node].count = 0;
  return left;
}

template <class SplitFn>
void AabbTree::buildTopDown(uint32_t n, SplitFn split) {
  nodes_.reserve(2 * size_t(n));  // at most n leaves, 2n - 1 nodes: never reallocated (pages are touched as used)
  struct Task {
    uint32_t node, begin, end;
  };
  std::vector<Task> tasks;
  nodes_.push_back({});
  tasks.push_back({0, 0, n});
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    const uint32_t mid = split(t.begin, t.end);
    if (mid == t.end) {
      makeLeaf(t.node, t.begin, t.end);
      continue;
    }
    const uint32_t left = addChildren(t.node);
    tasks.push_back({left, t.begin, mid});
    tasks.push_back({left + 1, mid, t.end});
  }
}

void AabbTree::buildMedian(uint32_t n, const std::function<Box3(uint32_t)>& boxOf) {
  // Median splits on contiguous (centroid, index) records. The tree is the one the comparator
  // defines (the same on every standard library): each split is the set of the n/2 smallest
  // (centroid, index) pairs, and a leaf lists its primitives in index order. Partitioning records
  // rather than indices keeps the walk over each range in cache.
  struct Item {
    Vec3 c;
    uint32_t index;
  };
  std::vector<Item> items(n);
  for (uint32_t i = 0; i < n; ++i) items[i] = {centroidOf(boxOf(i)), i};
  buildTopDown(n, [&](uint32_t begin, uint32_t end) {
    Box3 cbox;
    for (uint32_t i = begin; i < end; ++i) cbox.add(items[i].c);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (cbox.hi[k] - cbox.lo[k] > cbox.hi[axis] - cbox.lo[axis]) axis = k;
    if (end - begin <= kLeafSize || !(cbox.hi[axis] > cbox.lo[axis])) {
      for (uint32_t i = begin; i < end; ++i) order_[i] = items[i].index;
      return end;
    }
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                     [axis](const Item& a, const Item& b) {
                       if (a.c[axis] != b.c[axis]) return a.c[axis] < b.c[axis];
                       return a.index < b.index;  // deterministic order for equal keys
                     });
    return mid;
  });
}

void AabbTree::buildMorton(uint32_t n, const std::function<Box3(uint32_t)>& boxOf) {
  std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
  {
    std::vector<Vec3> centroid(n);
    Box3 cbox;
    for (uint32_t i = 0; i < n; ++i) cbox.add(centroid[i] = centroidOf(boxOf(i)));
    const MortonGrid grid(cbox);
    for (uint32_t i = 0; i < n; ++i) keyed[i] = {grid.code(centroid[i]), i};
  }
  MortonGrid::sort(keyed);
  for (uint32_t i = 0; i < n; ++i) order_[i] = keyed[i].second;
  buildTopDown(n, [&](uint32_t begin, uint32_t end) {
    if (end - begin <= kLeafSize) return end;
    const uint64_t first = keyed[begin].first, last = keyed[end - 1].first;
    if (first == last) return begin + (end - begin) / 2;
    // the first code with the highest differing bit set (the codes are sorted)
    int bit = 63;
    while (!(((first ^ last) >> bit) & 1)) --bit;
    const uint64_t key = last & (~0ull << bit);
    return uint32_t(std::lower_bound(keyed.begin() + begin, keyed.begin() + end, key,
                                     [](const std::pair<uint64_t, uint32_t>& e, uint64_t k) { return e.first < k; }) -
                    keyed.begin());
  });
}


Vec3 closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double len2 = dot(ab, ab);
  if (!(len2 > 0)) return a;
  double t = dot(p - a, ab) / len2;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return a + ab * t;
}

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  Vec3 bp = p - b;
  double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double den = d1 - d3;
    return den > 0 ? a + ab * (d1 / den) : a;
  }
  Vec3 cp = p - c;
  double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double den = d2 - d6;
    return den > 0 ? a + ac * (d2 / den) : a;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double den = (d4 - d3) + (d5 - d6);
    return den > 0 ? b + (c - b) * ((d4 - d3) / den) : b;
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
