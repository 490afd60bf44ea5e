// conformesh — defects of a stitched surface that the certificate rounds re-mesh away.
//
// Patches are meshed one by one and stitched through their shared curve samples, so the union
// can be non-manifold where two patches close the same small region on their own: the same
// three samples as a triangle in both (a corner wedge between two curves that both border), or
// the same two samples joined by a chord inside both. Each is found here with the patch that
// must put a vertex inside it; the pipeline re-meshes those patches with a required point.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh {

//! Triangles whose three vertices another triangle also has; of each such pair, the one in the
//! patch with more triangles (the one to re-mesh with a vertex inside it). Ascending.
//! `trianglePatch`: the patch of every triangle of `m`.
std::vector<size_t> doubledTriangles(const MeshBuffers& m, const std::vector<uint32_t>& trianglePatch);

//! Chords shared by patches: edges of `m` with three or more triangles, two of them from one
//! patch (a chord inside that patch between two of its boundary samples, which another patch or
//! a curve also joins). Per such patch and edge: {t, c}, the patch's first triangle t on the edge
//! and the corner c where the edge starts in t (corners c and (c + 1) % 3). Ascending.
std::vector<std::array<size_t, 2>> sharedChords(const MeshBuffers& m, const std::vector<uint32_t>& trianglePatch);

}  // namespace conformesh
