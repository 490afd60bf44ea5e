#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

#include "core/hilbert.h"

using conformesh::hilbertKey;

TEST_CASE("hilbertKey: the cells of an aligned 2^k block are one run of the curve, in unit steps") {
  // a Hilbert curve fills every aligned 2^k x 2^k block in 4^k consecutive steps, each to a
  // cell sharing a side with the one before
  for (const auto& [x0, y0] : std::vector<std::pair<uint32_t, uint32_t>>{{0, 0}, {16, 0}, {48, 32}, {65520, 65520}}) {
    std::vector<std::pair<uint64_t, std::pair<uint32_t, uint32_t>>> cells;
    for (uint32_t x = x0; x < x0 + 16; ++x)
      for (uint32_t y = y0; y < y0 + 16; ++y) cells.push_back({hilbertKey(x, y), {x, y}});
    std::sort(cells.begin(), cells.end());
    CHECK(cells.back().first - cells.front().first == 255);  // consecutive keys
    CHECK(cells.front().first % 256 == 0);
    for (size_t i = 1; i < cells.size(); ++i) {
      const auto [ax, ay] = cells[i - 1].second;
      const auto [bx, by] = cells[i].second;
      CHECK(std::abs(int(ax) - int(bx)) + std::abs(int(ay) - int(by)) == 1);
    }
  }
}

TEST_CASE("hilbertKey: distinct cells, distinct keys, within 4^16") {
  std::vector<uint64_t> keys;
  for (uint32_t x = 0; x < 65536; x += 4099)
    for (uint32_t y = 0; y < 65536; y += 4093) keys.push_back(hilbertKey(x, y));
  std::sort(keys.begin(), keys.end());
  CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  CHECK(keys.back() < (uint64_t(1) << 32));
  CHECK(hilbertKey(0, 0) == 0);
}
