// conformesh — positions along a Hilbert curve, for spatially coherent orders.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace conformesh {

//! Index of the cell (x, y) along a 2^16 x 2^16 Hilbert curve (the classic rotate-and-flip
//! formulation; Hilbert 1891): cells near each other on the curve are near each other in the plane.
inline uint64_t hilbertKey(uint32_t x, uint32_t y) {
  uint64_t d = 0;
  for (uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += uint64_t(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = 0xFFFFu - x;
        y = 0xFFFFu - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

//! The points xy[2i], xy[2i + 1] for i in `ids`, ordered along a Hilbert curve over their bounding
//! square (2^16 cells a side; ties by index): points near each other in the list are near each
//! other in the plane. The coordinates must be finite.
inline std::vector<uint32_t> hilbertOrder(const double* xy, const std::vector<uint32_t>& ids) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (uint32_t i : ids) {
    x0 = std::min(x0, xy[2 * size_t(i)]), x1 = std::max(x1, xy[2 * size_t(i)]);
    y0 = std::min(y0, xy[2 * size_t(i) + 1]), y1 = std::max(y1, xy[2 * size_t(i) + 1]);
  }
  const double sc = 65535.0 / std::max(std::max(x1 - x0, y1 - y0), 1e-300);
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  keyed.reserve(ids.size());
  for (uint32_t i : ids) {
    const uint32_t qx = uint32_t(std::min(65535.0, (xy[2 * size_t(i)] - x0) * sc));
    const uint32_t qy = uint32_t(std::min(65535.0, (xy[2 * size_t(i) + 1] - y0) * sc));
    keyed.emplace_back(hilbertKey(qx, qy), i);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& k : keyed) order.push_back(k.second);
  return order;
}

}  // namespace conformesh
