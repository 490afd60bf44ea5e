// conformesh — mesh readers and writers (OBJ, OFF, STL ascii/binary, PLY ascii/binary LE/BE).
//
// Readers work on bytes (no file system needed: the same code runs in WASM). The format is
// detected from the content, with the file name's extension as a hint. Errors throw
// conformesh::Error, stage Read:
//   ParseError           the bytes are not a valid file of the format; the message gives the line
//                        (text formats, 1-based) or the byte offset (binary formats, 0-based).
//                        Also: a face with fewer than 3 vertices, an unrecognised format, a
//                        truncated binary STL (size != 84 + 50·n).
//   EmptyMesh            no vertices or no faces.
//   IndexOutOfRange      a face refers to a vertex that does not exist (OBJ: also index 0).
//   NonFiniteCoordinate  a NaN / infinite coordinate (text "nan", "inf", "1e999" included).
//   TooLarge             a header count (OFF, PLY) cannot fit in the remaining bytes, or the mesh
//                        would have more than 2^32 - 2 vertices. Checked before anything is
//                        allocated from the count.
//   InvalidArgument      a bad option: weldTolerance negative, NaN, infinite, or so small that
//                        coordinates / tolerance exceed 2^50 grid cells.
// Degenerate faces (repeated indices, zero area) are kept: validation (mesh/validate) drops them.
// Vertices are kept as in the file, including vertices no face uses (except after welding).
// A UTF-8 byte order mark at the start of a text file is skipped. Hosts are assumed little endian
// (x86, ARM, WASM): binary STL floats are read in place.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "conformesh/buffers.h"

namespace conformesh {

enum class MeshFormat { Auto, Obj, Off, StlAscii, StlBinary, PlyAscii, PlyBinaryLE, PlyBinaryBE };

//! "obj", "off", "stl-ascii", "stl", "ply-ascii", "ply", "ply-be", "auto".
const char* formatName(MeshFormat f);
//! Parse a format name as above, or a file extension / file name ("obj", ".stl", "PLY",
//! "dir/bunny.off"); Auto if unknown. For "stl" and "ply" extensions the answer is the binary
//! variant; readers accept either variant whatever was given.
MeshFormat formatFromName(const std::string& nameOrExtension);

//! Detect the format from the content alone (Auto when unrecognised). Order: "ply" magic (the
//! header's format line gives the variant); binary STL when the size is exactly 84 + 50·n with n
//! the header's triangle count (even when the 80-byte header begins with "solid"); "solid" → ascii
//! STL; an OFF header keyword ([ST][C][N][4][n]OFF) → OFF; a first OBJ keyword (v, vt, vn, f, o,
//! g, s, usemtl, mtllib, ...) → OBJ.
MeshFormat detectFormat(const uint8_t* data, size_t size);

struct ReadOptions {
  //! Auto: detect from the content, then from `fileName`'s extension. A forced format is read as
  //! that format (for PLY the header decides ascii / binary; StlBinary also accepts trailing
  //! bytes after the last triangle, with a warning).
  MeshFormat format = MeshFormat::Auto;
  std::string fileName;  //!< only a hint for detection and a prefix for messages
  //! STL stores no shared vertices: exactly equal positions are always welded (on the exact bits,
  //! -0 == +0; vertex order = first appearance). A tolerance > 0 (absolute length units) also
  //! welds, in every format, each vertex to the first earlier kept vertex within that Euclidean
  //! distance (grid hashing, deterministic). 0: no tolerance weld.
  double weldTolerance = 0.0;
  //! OBJ `vt` / PLY u,v (or s,t / texture_u,texture_v) vertex properties into mesh.uvs. OBJ uvs
  //! go to mesh.uvs when every vertex used by a face has one vt value; with uv seams (a vertex
  //! with several) they are the per-corner attribute "uv" instead. Dropped (warning) when some
  //! face corner has no vt.
  bool readUvs = true;
  //! Other vertex data into mesh.attributes (MeshAttribute): OBJ `vn` as "normal" (per vertex
  //! when every vertex has one value, else per corner); PLY red/green/blue[/alpha] (or
  //! diffuse_red, ...) as "color" scaled to [0, 1] from integer types (uchar / 255, ushort /
  //! 65535), nx/ny/nz as "normal", and every other scalar vertex property as a 1-component
  //! attribute of its own name.
  bool readAttributes = true;
};

struct ReadResult {
  MeshBuffers mesh;                      //!< triangles (polygons fan-triangulated: 0,i,i+1)
  MeshFormat format = MeshFormat::Auto;  //!< the format actually read
  std::vector<std::string> warnings;     //!< non-fatal findings (welded vertices, dropped uvs)
};

//! Read a mesh from bytes. Throws conformesh::Error (stage Read) as listed at the top of this file.
//! Memory and time are O(size of the input): no count from a header is trusted before it is
//! checked against the bytes that remain.
ReadResult readMesh(const uint8_t* data, size_t size, const ReadOptions& options = {});
inline ReadResult readMesh(const std::vector<uint8_t>& bytes, const ReadOptions& options = {}) {
  return readMesh(bytes.data(), bytes.size(), options);
}

struct WriteOptions {
  //! OBJ: write `vt` and `f a/a b/b c/c` when mesh.uvs is non-empty, or one `vt` per distinct
  //! value of a per-corner attribute "uv" (`f a/i b/j c/k`). PLY: write u, v vertex properties
  //! (double), or a per-corner "uv" as the face list property `texcoord` (6 doubles, MeshLab's).
  //! Ignored by OFF and STL.
  bool writeUvs = true;
  //! mesh.attributes: OBJ writes "normal" as `vn` (per vertex: `vn` i is vertex i's; per corner:
  //! one per distinct value) and drops the others; PLY writes every per-vertex attribute as
  //! vertex properties ("normal" as double nx ny nz, "color" as uchar red green blue [alpha],
  //! 255 · value rounded, others as double by name, name_0, name_1, ... for several components)
  //! and every per-corner one as a face list property of 3 · components doubles by its name (the
  //! PLY reader reads back only `texcoord`). Ignored by OFF and STL.
  bool writeAttributes = true;
};

//! Write a mesh. Supported: Obj, Off, StlAscii, StlBinary, PlyBinaryLE, PlyBinaryBE, PlyAscii.
//! Text formats write each coordinate in the shortest of 15, 16 or 17 significant digits that
//! reads back to the same double: a round trip gives bit-identical positions. PLY binary writes
//! doubles (exact). Binary STL stores 32-bit floats by definition: it is the one lossy writer
//! (round trip exact only for float-representable positions). STL stores no indices: reading it
//! back welds equal positions, so vertices come back in first-appearance order.
//! Throws conformesh::Error, stage Write: InvalidArgument (Auto or bad buffer sizes),
//! IndexOutOfRange, NonFiniteCoordinate, TooLarge (binary STL with more than 2^32 - 1 triangles).
std::vector<uint8_t> writeMesh(const MeshBuffers& mesh, MeshFormat format, const WriteOptions& options = {});

}  // namespace conformesh
