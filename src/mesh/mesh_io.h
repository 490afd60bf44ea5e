// conformesh — mesh readers and writers (OBJ, OFF, STL ascii/binary, PLY ascii/binary LE/BE).
//
// Readers work on bytes (no file system needed: the same code runs in WASM). The format is
// detected from the content, with the file name's extension as a hint. Errors throw
// conformesh::Error with Code::ParseError (message gives the line, or the byte offset for binary
// formats), Code::EmptyMesh, Code::IndexOutOfRange or Code::NonFiniteCoordinate, stage Read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh_buffers.h"

namespace conformesh {

enum class MeshFormat { Auto, Obj, Off, StlAscii, StlBinary, PlyAscii, PlyBinaryLE, PlyBinaryBE };

//! "obj", "off", "stl-ascii", "stl", "ply-ascii", "ply", "ply-be", "auto".
const char* formatName(MeshFormat f);
//! Parse a format name as above, or a file extension ("obj", ".stl", "PLY"); Auto if unknown.
MeshFormat formatFromName(const std::string& nameOrExtension);

struct ReadOptions {
  MeshFormat format = MeshFormat::Auto;  //!< Auto: detect from content, then `fileName`'s extension
  std::string fileName;                  //!< only a hint for detection and for messages
  //! STL has no shared vertices: exactly equal positions are always welded. A tolerance > 0 also
  //! welds vertices closer than it (absolute units). Applies to every format when > 0.
  double weldTolerance = 0.0;
  bool readUvs = true;  //!< OBJ vt: kept when every used vertex has exactly one vt
};

struct ReadResult {
  MeshBuffers mesh;                   //!< triangles (polygons fan-triangulated)
  MeshFormat format = MeshFormat::Auto;  //!< the format actually read
  std::vector<std::string> warnings;  //!< non-fatal findings (welded vertices, skipped elements)
};

//! Read a mesh from bytes. Throws conformesh::Error (stage Read) on failure.
ReadResult readMesh(const uint8_t* data, size_t size, const ReadOptions& options = {});
inline ReadResult readMesh(const std::vector<uint8_t>& bytes, const ReadOptions& options = {}) {
  return readMesh(bytes.data(), bytes.size(), options);
}

struct WriteOptions {
  bool writeUvs = true;  //!< OBJ: write `vt` (and f a/a) when mesh.uvs is non-empty
};

//! Write a mesh. Supported: Obj, Off, StlAscii, StlBinary, PlyBinaryLE (PlyAscii too).
//! Text formats write positions with 17 significant digits: reading back gives the same doubles.
//! Throws conformesh::Error (stage Write) for unsupported formats or invalid buffers.
std::vector<uint8_t> writeMesh(const MeshBuffers& mesh, MeshFormat format, const WriteOptions& options = {});

}  // namespace conformesh
