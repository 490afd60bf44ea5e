// conformesh — per-vertex and per-corner mesh attributes (MeshAttribute, core/mesh_buffers.h):
// checks, the seams where per-corner values jump, and interpolation at a point of a face.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh {

//! Throws Error(InvalidArgument, stage) unless mesh.uvs is empty or 2 per vertex and every
//! attribute of `mesh` has a name, >= 1 component and exactly itemCount · components values, and Error(NonFiniteCoordinate, stage)
//! for a NaN or infinite value.
void checkAttributes(const MeshBuffers& mesh, Stage stage);

//! True when `mesh` carries data to interpolate: uvs or any attribute.
inline bool hasAttributes(const MeshBuffers& mesh) { return !mesh.uvs.empty() || !mesh.attributes.empty(); }

//! The seams of the per-corner attributes: every edge (a vertex pair, smaller index first, sorted)
//! whose two triangles give different values (any attribute, any component) at one of its ends,
//! and every edge with a single triangle or more than two is not a seam. A uv seam is where a
//! texture chart ends: remesh keeps these edges as feature curves (RemeshOptions::carryAttributes).
//! Values are compared exactly, as a file gives them. Triangles validation drops (a repeated vertex,
//! exactly zero area) are left out. Pre: checkAttributes passed.
std::vector<std::array<uint32_t, 2>> attributeSeams(const MeshBuffers& mesh);

//! Per triangle side (side k of triangle t, from corner k to k + 1, is item 3·t + k), the
//! triangle across it when that edge has two triangles and is not a seam (attributeSeams), else
//! UINT32_MAX: walking these never crosses a seam, so per-corner values stay continuous.
std::vector<uint32_t> neighboursWithinCharts(const MeshBuffers& mesh);

//! The value of attribute `a` at the point with barycentric coordinates `bary` (w.r.t. corners
//! 0, 1, 2) of triangle `t` of `mesh`: the affine combination of the three corners' values (per
//! corner: the triangle's own corners; per vertex: its vertices' values), written to
//! out[0 .. a.components). Normals ("normal", 3 components) are renormalized to unit length when
//! the combination is not zero.
void interpolateAttribute(const MeshBuffers& mesh, const MeshAttribute& a, uint32_t t, const double bary[3], double* out);

}  // namespace conformesh
