// conformesh — generated test and sample surfaces (our own constructions, exact topology known).
//
// All are consistently oriented with normals pointing outwards (up, +z, for the flat ones) and
// every triangle has positive area. Sizes are in the units of the arguments.
#pragma once

#include "core/mesh_buffers.h"

namespace conformesh {

//! Unit sphere: icosahedron, each triangle split in 4 `subdivisions` times, projected to the
//! sphere. 10·4^s + 2 vertices, 20·4^s triangles. Closed, genus 0. s in [0, 8].
MeshBuffers makeIcosphere(int subdivisions);

//! Torus of radii R > r > 0 around the z axis, `ringSegments` × `tubeSegments` quads (each ≥ 3).
//! Closed, genus 1.
MeshBuffers makeTorus(int ringSegments, int tubeSegments, double R, double r);

//! Flat disk of radius `radius` in the plane z = 0: a centre vertex and `rings` rings of
//! `sectors` vertices (rings ≥ 1, sectors ≥ 3). One boundary loop.
MeshBuffers makeDisk(int rings, int sectors, double radius);

//! Flat annulus innerRadius < r < outerRadius in z = 0, `rings` ≥ 1 bands of `sectors` ≥ 3
//! quads. Two boundary loops.
MeshBuffers makeAnnulus(int rings, int sectors, double innerRadius, double outerRadius);

//! Axis-aligned cube [-h, h]^3, each face an n × n grid of quads split into triangles (n ≥ 1).
//! Closed, genus 0, 12 sharp (90°) edges.
MeshBuffers makeCube(int n, double halfSize);

//! A CAD-like part: the box [-outer, outer]² × [0, height] with a square through-hole of half
//! size `hole` (0 < hole < outer). `n` ≥ 1 segments per straight side. Closed, genus 1, all
//! dihedral angles 0 or ±90° (the hole's four vertical corner edges are concave).
MeshBuffers makeBoxWithHole(int n, double outer, double hole, double height);

}  // namespace conformesh
