// conformesh — positions along a Hilbert curve, for spatially coherent orders.
#pragma once

#include <cstdint>
#include <utility>

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

}  // namespace conformesh
