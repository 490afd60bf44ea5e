// conformesh — internal: the CDT built on Triangulation, with the segment bookkeeping that the
// refinement continues to use. Not a public header.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "planar/cdt.h"
#include "planar/triangulation.h"

namespace conformesh::planar {

struct CdtState {
  Triangulation tri;
  uint32_t nInput = 0;             // input vertex count
  uint32_t nInputSegments = 0;     // input segments; ids >= this are convex-hull edges
  std::vector<uint32_t> segA, segB;  // endpoints per segment id (after duplicate merge)
  std::vector<int32_t> segMarker;
  std::vector<uint32_t> rep;         // per input vertex: its representative (duplicates merged)
  std::vector<int32_t> vseg;         // per vertex: segment id or -1
  std::vector<double> vparam;        // per vertex: parameter on vseg
  std::vector<uint32_t> segDegree;   // per input vertex: constrained edges at it
  std::unordered_map<uint64_t, uint32_t> subseg;  // input-vertex pair -> segment id

  static uint64_t key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t(a) << 32) | b;
  }
  //! Segment id of the constrained edge (u, v), or -1.
  int32_t segmentOf(uint32_t u, uint32_t v) const {
    if (u >= nInput && vseg[u] >= 0) return vseg[u];
    if (v >= nInput && vseg[v] >= 0) return vseg[v];
    auto it = subseg.find(key(u, v));
    return it == subseg.end() ? -1 : int32_t(it->second);
  }
  bool inDomain(uint32_t t) const { return (tri.tf[t] & (kIsGhost | kOutside | kDead)) == 0; }
};

//! Build the CDT and classify the domain. Throws as triangulatePslg.
void buildCdt(const Pslg& pslg, const CdtOptions& options, const ProgressFn& progress, CdtState& s);
//! Domain triangles, constrained edges and per-vertex segment data of the state. With
//! `consume`, the vertex arrays are moved out of `s` (it must not be used afterwards).
void extractMesh(CdtState& s, PlanarMesh& out, bool consume = false);

}  // namespace conformesh::planar
