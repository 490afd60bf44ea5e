// conformesh — format names, detection, and the readMesh entry point (dispatch to the readers
// in read_*.cpp, then the checks every format shares).
#include "mesh/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "mesh/io_detail.h"
#include "mesh/weld_vertices.h"

namespace conformesh {

using namespace io_detail;

const char* formatName(MeshFormat f) {
  switch (f) {
    case MeshFormat::Auto: return "auto";
    case MeshFormat::Obj: return "obj";
    case MeshFormat::Off: return "off";
    case MeshFormat::StlAscii: return "stl-ascii";
    case MeshFormat::StlBinary: return "stl";
    case MeshFormat::PlyAscii: return "ply-ascii";
    case MeshFormat::PlyBinaryLE: return "ply";
    case MeshFormat::PlyBinaryBE: return "ply-be";
  }
  return "auto";
}

MeshFormat formatFromName(const std::string& nameOrExtension) {
  std::string s = nameOrExtension;
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::StlAscii, MeshFormat::StlBinary,
                       MeshFormat::PlyAscii, MeshFormat::PlyBinaryLE, MeshFormat::PlyBinaryBE})
    if (s == formatName(f)) return f;
  size_t dot = s.find_last_of('.');
  size_t slash = s.find_last_of("/\\");
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) s = s.substr(dot + 1);
  if (s == "obj") return MeshFormat::Obj;
  if (s == "off") return MeshFormat::Off;
  if (s == "stl") return MeshFormat::StlBinary;
  if (s == "ply") return MeshFormat::PlyBinaryLE;
  return MeshFormat::Auto;
}

namespace {

bool startsWithWord(const uint8_t* data, size_t size, const char* word) {
  size_t i = 0;
  while (i < size && (isSpace(char(data[i])) || data[i] == '\n')) ++i;
  size_t n = std::strlen(word);
  if (size - i < n) return false;
  for (size_t k = 0; k < n; ++k)
    if (std::tolower(data[i + k]) != word[k]) return false;
  return size - i == n || isSpace(char(data[i + n])) || data[i + n] == '\n';
}

bool binaryStlSizeMatches(const uint8_t* data, size_t size) {
  if (size < 84) return false;
  uint64_t n = uint64_t(data[80]) | (uint64_t(data[81]) << 8) | (uint64_t(data[82]) << 16) | (uint64_t(data[83]) << 24);
  return 84 + 50 * n == uint64_t(size);
}

MeshFormat plyVariant(const uint8_t* data, size_t size) {
  // "ply" line, then (possibly after comments) "format <kind> 1.0".
  const char* p = reinterpret_cast<const char*>(data);
  const size_t n = std::min<size_t>(size, 4096);
  std::string head(p, n);
  size_t f = head.find("format ");
  if (f == std::string::npos) return MeshFormat::PlyAscii;
  if (head.compare(f + 7, 20, "binary_little_endian") == 0) return MeshFormat::PlyBinaryLE;
  if (head.compare(f + 7, 17, "binary_big_endian") == 0) return MeshFormat::PlyBinaryBE;
  return MeshFormat::PlyAscii;
}

}  // namespace

MeshFormat detectFormat(const uint8_t* data, size_t size) {
  if (size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r'))
    return plyVariant(data, size);
  if (binaryStlSizeMatches(data, size)) return MeshFormat::StlBinary;
  if (startsWithWord(data, size, "solid")) return MeshFormat::StlAscii;
  if (looksLikeOff(data, size)) return MeshFormat::Off;
  if (looksLikeObj(data, size)) return MeshFormat::Obj;
  return MeshFormat::Auto;
}

ReadResult readMesh(const uint8_t* data, size_t size, const ReadOptions& options) {
  if (!(options.weldTolerance >= 0.0) || !std::isfinite(options.weldTolerance))
    fail(Code::InvalidArgument, Stage::Read, "weldTolerance must be a finite number >= 0");
  static const uint8_t kNothing = 0;
  if (!data) data = &kNothing;  // size is then 0

  // A UTF-8 byte order mark before a text format is skipped (some Windows tools write one).
  if (size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF && !binaryStlSizeMatches(data, size)) {
    data += 3;
    size -= 3;
  }
  Source src;
  src.data = data;
  src.size = size;
  src.name = options.fileName;
  MeshFormat format = options.format;
  src.forced = format != MeshFormat::Auto;
  if (size == 0) src.failPlain(Code::EmptyMesh, "empty input (0 bytes)");
  if (format == MeshFormat::Auto) format = detectFormat(data, size);
  if (format == MeshFormat::Auto && !options.fileName.empty()) {
    format = formatFromName(options.fileName);
    src.forced = format != MeshFormat::Auto;
  }
  if (format == MeshFormat::Auto)
    src.failPlain(Code::ParseError,
                  "unrecognised mesh format (not OBJ, OFF, STL or PLY by content; give a file name or a format)");
  if (src.name.empty()) src.name = formatName(format);

  ReadResult result;
  switch (format) {
    case MeshFormat::Obj: readObj(src, options, result); break;
    case MeshFormat::Off: readOff(src, options, result); break;
    case MeshFormat::StlAscii: readStlAscii(src, options, result); break;
    case MeshFormat::StlBinary:
      // A forced or extension-given "stl" may still be ascii.
      if (!binaryStlSizeMatches(data, size) && startsWithWord(data, size, "solid") &&
          !std::memchr(data, '\0', std::min<size_t>(size, 4096)))
        readStlAscii(src, options, result);
      else
        readStlBinary(src, options, result);
      break;
    case MeshFormat::PlyAscii:
    case MeshFormat::PlyBinaryLE:
    case MeshFormat::PlyBinaryBE: readPly(src, options, result); break;
    case MeshFormat::Auto: break;
  }

  MeshBuffers& mesh = result.mesh;
  if (mesh.vertexCount() == 0) src.failPlain(Code::EmptyMesh, "no vertices");
  if (mesh.triangleCount() == 0) src.failPlain(Code::EmptyMesh, "no faces");
  const size_t nv = mesh.vertexCount();
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      src.failPlain(Code::NonFiniteCoordinate, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
  for (uint32_t t : mesh.triangles)
    if (t >= nv) src.failPlain(Code::InternalError, "reader produced a vertex index out of range");
  if (!mesh.uvs.empty() && mesh.uvs.size() != 2 * nv) mesh.uvs.clear();

  if (options.weldTolerance > 0.0) {
    size_t removed = weldVertices(mesh, options.weldTolerance, Stage::Read);
    if (removed)
      result.warnings.push_back("welded " + std::to_string(removed) + " vertices within tolerance " +
                                std::to_string(options.weldTolerance));
  }
  return result;
}

}  // namespace conformesh
