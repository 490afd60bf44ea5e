// conformesh — remesh stage 5: the patches' meshings joined into one mesh. The curve samples are
// the first output vertices (shared by the patches on both sides of a curve), then each patch's
// interior vertices in patch order.
#pragma once

#include "remesh/pipeline.h"

namespace conformesh::pipeline {

//! The stitched mesh. trianglePatch: per output triangle its patch. vertexFace: per output
//! vertex, a face of the validated input it lies on or near (its lift's, or one beside its curve
//! sample's input edge or vertex), kNone when unknown: a hint for the report's distance check.
MeshBuffers stitch(const Surface& surf, const Meshing& m, std::vector<uint32_t>& trianglePatch,
                   std::vector<uint32_t>& vertexFace);

//! Every patch's planar data as stitched into `out` (same vertex numbering as stitch()).
std::vector<RemeshPatch> patchSnapshot(const Meshing& m, const MeshBuffers& out);

//! RemeshOptions::forceTopologyDefect: a flipped copy (b, a, c') of triangle 0 (a, b, c), c' a new
//! vertex at c, so edge ab has three triangles. The per-vertex and per-triangle arrays grow with it.
void addNonManifoldEdge(MeshBuffers& m, std::vector<uint32_t>& vertexFace, std::vector<uint8_t>& exemptVertex,
                        std::vector<uint32_t>& triPatch);

}  // namespace conformesh::pipeline
