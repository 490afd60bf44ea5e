// conformesh — sorting by a small integer primary key (a vertex index) in linear time.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace conformesh {

//! Sort v into the order std::sort(v, less) gives, where bucket(x) in [0, buckets) is the primary
//! key of `less` (less(x, y) whenever bucket(x) < bucket(y)): a counting sort by bucket, then
//! std::sort inside each bucket (a vertex's few edges or faces). `less` must be a strict total
//! order on the items (ties broken, e.g. by an index), so the result does not depend on the method.
//! Keys sparser than the items (more than 4 buckets per item), or any key outside [0, buckets),
//! fall back to std::sort.
template <class T, class Bucket, class Less>
void bucketSort(std::vector<T>& v, size_t buckets, Bucket bucket, Less less) {
  if (v.size() < 2) return;
  bool inRange = buckets <= 4 * v.size() + 1024;  // sparse keys (huge indices): no table
  for (size_t i = 0; i < v.size() && inRange; ++i) inRange = size_t(bucket(v[i])) < buckets;
  if (!inRange) {  // or a key outside [0, buckets) (a caller's bad input): the plain sort
    std::sort(v.begin(), v.end(), less);
    return;
  }
  std::vector<uint32_t> start(buckets + 1, 0);
  for (const T& x : v) ++start[size_t(bucket(x)) + 1];
  for (size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<T> out(v.size());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const T& x : v) out[fill[size_t(bucket(x))]++] = x;
  }
  for (size_t b = 0; b < buckets; ++b)
    if (start[b + 1] - start[b] > 1) std::sort(out.begin() + start[b], out.begin() + start[b + 1], less);
  v.swap(out);
}

}  // namespace conformesh
