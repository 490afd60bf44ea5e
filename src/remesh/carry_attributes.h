// conformesh — the input's attributes on the remeshed surface: every output corner located on
// the input (its pull-back point: an input face and barycentric coordinates, on its triangle's
// side of an attribute seam), and the input's uvs and attributes interpolated there.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh {

//! Per corner of the output (corner c of triangle t is 3·t + c).
struct CornerPoints {
  std::vector<uint32_t> face;        //!< 3·nF: the input triangle (input numbering) the corner's vertex lies on
  std::vector<double> barycentric;   //!< 9·nF: its barycentric coordinates there, w.r.t. that triangle's corners 0, 1, 2
};

//! Locate every corner of `output` (whose vertices lie on the surface of `input`) on `input`.
//! A vertex is on the input faces around its closest one (AABB tree) that are as close, within
//! 1e-9 · the input's bounding-box diagonal. When there are several (the vertex is on an input
//! edge or vertex) and the input has per-corner attributes, each corner takes the face its
//! triangle is on: the first of them reached by a breadth-first walk over input faces from the
//! face closest to the triangle's centroid, across edges that are not attribute seams
//! (neighboursWithinCharts), at most 4096 faces (else the one closest to the centroid). With the
//! seams kept as output edges (remesh keeps them as curves) every triangle is on one side of
//! each, so the corner gets its values from that side, even where a chart meets itself across a
//! seam. Zero-area input faces are never chosen when another is as close. `vertexHint`: per
//! output vertex an input face at or near it, or UINT32_MAX (a start for the search; may be
//! empty). Cost: one closest-point query per output vertex, one more per triangle at a seam.
CornerPoints locateCorners(const MeshBuffers& input, const MeshBuffers& output, const std::vector<uint32_t>& vertexHint);

//! Fill output.uvs and output.attributes from input.uvs and input.attributes, interpolated at
//! the corners' points (interpolateAttribute, mesh/mesh_attributes.h): a per-vertex input
//! attribute gives a per-vertex output one (taken at the vertex's first corner: the input's
//! value is continuous), a per-corner one a per-corner output one, each corner on its own side
//! of the seams. Vertices no triangle uses get zeros.
void interpolateAttributes(const MeshBuffers& input, const CornerPoints& points, MeshBuffers& output);

}  // namespace conformesh
