// conformesh — the flat mesh arrays used at every boundary (files, C++ API, JS).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/status.h"

namespace conformesh {

//! A triangle mesh as flat arrays, GL style (maps one-to-one onto three.js BufferAttributes).
//!   positions  3·nV doubles, x y z per vertex
//!   triangles  3·nF vertex indices, counter-clockwise seen from outside
//!   uvs        empty, or 2·nV doubles (per-vertex planar coordinates, e.g. from flatten)
struct MeshBuffers {
  std::vector<double> positions;
  std::vector<uint32_t> triangles;
  std::vector<double> uvs;

  size_t vertexCount() const { return positions.size() / 3; }
  size_t triangleCount() const { return triangles.size() / 3; }
};

//! Progress callback: stage and fraction in [0, 1] (monotone within a call). Return false to
//! cancel; the running function then stops with Code::Cancelled.
using ProgressFn = std::function<bool(Stage, double)>;

}  // namespace conformesh
