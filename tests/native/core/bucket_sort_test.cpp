#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "core/bucket_sort.h"

using namespace conformesh;

TEST_CASE("bucketSort gives std::sort's order, dense and sparse keys") {
  std::mt19937 rng(11);
  using Item = std::array<uint32_t, 3>;  // (bucket key, second key, index)
  const auto less = [](const Item& x, const Item& y) { return x < y; };
  for (uint32_t keys : {1u, 7u, 1000u, 4000000000u}) {
    std::uniform_int_distribution<uint32_t> k(0, keys - 1), s(0, 5);
    std::vector<Item> v(5000);
    for (uint32_t i = 0; i < v.size(); ++i) v[i] = {k(rng), s(rng), i};
    std::vector<Item> ref = v;
    std::sort(ref.begin(), ref.end(), less);
    uint32_t maxKey = 0;
    for (const Item& x : v) maxKey = std::max(maxKey, x[0]);
    bucketSort(v, size_t(maxKey) + 1, [](const Item& x) { return x[0]; }, less);
    CAPTURE(keys);
    CHECK(v == ref);
  }
  // a key outside the announced range: the plain sort, not a write out of bounds
  std::vector<Item> bad = {{9, 0, 0}, {2, 0, 1}, {5, 0, 2}};
  bucketSort(bad, 4, [](const Item& x) { return x[0]; }, less);
  CHECK(bad == std::vector<Item>{{2, 0, 1}, {5, 0, 2}, {9, 0, 0}});
  std::vector<Item> one = {{3, 0, 0}};
  bucketSort(one, 4, [](const Item& x) { return x[0]; }, less);
  CHECK(one.size() == 1);
}
