// conformesh — welding of coincident vertices.
#pragma once

#include <cstddef>

#include "core/mesh_buffers.h"

namespace conformesh {

//! Merge coincident vertices of `mesh` in place and renumber its triangles.
//!   tolerance == 0: vertices with exactly equal coordinates (same doubles; -0 == +0) merge.
//!   tolerance  > 0: each vertex, in index order, merges into the lowest-indexed earlier kept
//!                   vertex within Euclidean distance <= tolerance (absolute length units), else
//!                   it is kept. Grid hashing with cell size = tolerance and the 27 neighbour
//!                   cells. Not transitive (a chain a~b~c with |a-c| > tolerance may keep c).
//! Kept vertices stay in their original relative order; a kept vertex keeps its position, uv and
//! per-vertex attributes (per-corner attributes are unchanged: the triangles keep their corners).
//! Triangles that become degenerate are kept (validation drops them). O(n) expected time.
//! Returns the number of vertices removed. Throws Error(InvalidArgument) for a negative or NaN
//! tolerance, or one so small that coordinates / tolerance exceeds 2^50 cells;
//! Error(NonFiniteCoordinate) for a non-finite position; Error(IndexOutOfRange) for a bad index.
size_t weldVertices(MeshBuffers& mesh, double tolerance = 0.0, Stage stage = Stage::Read);

}  // namespace conformesh
