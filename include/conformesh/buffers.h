// conformesh — the flat mesh arrays used at every boundary (files, C++ API, JS).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "conformesh/status.h"

namespace conformesh {

//! Data attached to a mesh's vertices or triangle corners (texture coordinates, normals, colours,
//! any scalar), as read from a file and carried through remesh.
//!   name        "uv" (2 components), "normal" (3), "color" (3 or 4, each in [0, 1]) or a PLY
//!               vertex property's own name (1 component)
//!   components  values per item, >= 1
//!   perCorner   false: one item per vertex, values nV·components; true: one item per triangle
//!               corner (corner c of triangle t is item 3·t + c), values 3·nF·components. Per
//!               corner is how a file says that a vertex has several values (an OBJ vertex on a
//!               uv seam has one vt per side); three.js needs such vertices split
//!               (conformesh/three does it).
//! A per-vertex uv is MeshBuffers::uvs, never an attribute "uv" with perCorner false.
struct MeshAttribute {
  std::string name;
  uint32_t components = 1;
  bool perCorner = false;
  std::vector<double> values;

  //! Items the values should hold for a mesh of `vertices` vertices and `triangles` triangles.
  size_t itemCount(size_t vertices, size_t triangles) const { return perCorner ? 3 * triangles : vertices; }
};

//! A triangle mesh as flat arrays, GL style (maps one-to-one onto three.js BufferAttributes).
//!   positions  3·nV doubles, x y z per vertex
//!   triangles  3·nF vertex indices, counter-clockwise seen from outside
//!   uvs        empty, or 2·nV doubles (per-vertex planar coordinates, e.g. from flatten, or
//!              texture coordinates read from a file where every vertex has one)
//!   attributes other data of the input carried along (see MeshAttribute)
struct MeshBuffers {
  std::vector<double> positions;
  std::vector<uint32_t> triangles;
  std::vector<double> uvs;
  std::vector<MeshAttribute> attributes;

  size_t vertexCount() const { return positions.size() / 3; }
  size_t triangleCount() const { return triangles.size() / 3; }
};

//! Progress callback: stage and fraction in [0, 1] (monotone within a call). Return false to
//! cancel; the running function then stops with Code::Cancelled.
using ProgressFn = std::function<bool(Stage, double)>;

}  // namespace conformesh
