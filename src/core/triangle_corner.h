// conformesh — which corner of a triangle a vertex is.
#pragma once

#include <cstdint>

namespace conformesh {

//! The corner (0, 1 or 2) of a triangle, given by its three vertex indices t, at vertex v, which
//! it has. Without a branch: which corner it is follows no pattern a predictor could learn.
inline int cornerOf(const uint32_t* t, uint32_t v) { return int(t[1] == v) + 2 * int(t[2] == v); }

}  // namespace conformesh
