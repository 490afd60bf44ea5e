// conformesh — mesh writers: OBJ (optional vt), OFF, STL ascii and binary, PLY ascii and binary
// (little or big endian, double coordinates, uint32 indices).
#include <cmath>
#include <string>
#include <vector>

#include "mesh/io_detail.h"

namespace conformesh {

using namespace io_detail;

namespace {

void checkBuffers(const MeshBuffers& mesh) {
  if (mesh.positions.size() % 3 != 0)
    fail(Code::InvalidArgument, Stage::Write, "positions size is not a multiple of 3");
  if (mesh.triangles.size() % 3 != 0)
    fail(Code::InvalidArgument, Stage::Write, "triangles size is not a multiple of 3");
  const size_t nv = mesh.vertexCount();
  if (!mesh.uvs.empty() && mesh.uvs.size() != 2 * nv)
    fail(Code::InvalidArgument, Stage::Write, "uvs must be empty or hold 2 values per vertex");
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      fail(Code::NonFiniteCoordinate, Stage::Write, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
  for (size_t i = 0; i < mesh.uvs.size(); ++i)
    if (!std::isfinite(mesh.uvs[i]))
      fail(Code::NonFiniteCoordinate, Stage::Write, "vertex " + std::to_string(i / 2) + " has a non-finite uv");
  for (uint32_t t : mesh.triangles)
    if (t >= nv) fail(Code::IndexOutOfRange, Stage::Write, "triangle index " + std::to_string(t) + " >= vertex count");
}

std::vector<uint8_t> toBytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

void appendXYZ(std::string& out, const double* p) {
  appendDouble(out, p[0]);
  out += ' ';
  appendDouble(out, p[1]);
  out += ' ';
  appendDouble(out, p[2]);
}

std::string writeObj(const MeshBuffers& mesh, bool uvs) {
  std::string s = "# conformesh\n";
  const size_t nv = mesh.vertexCount();
  for (size_t v = 0; v < nv; ++v) {
    s += "v ";
    appendXYZ(s, &mesh.positions[3 * v]);
    s += '\n';
  }
  if (uvs)
    for (size_t v = 0; v < nv; ++v) {
      s += "vt ";
      appendDouble(s, mesh.uvs[2 * v]);
      s += ' ';
      appendDouble(s, mesh.uvs[2 * v + 1]);
      s += '\n';
    }
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    s += 'f';
    for (int k = 0; k < 3; ++k) {
      const std::string i = std::to_string(mesh.triangles[3 * t + k] + uint64_t(1));
      s += ' ';
      s += i;
      if (uvs) s += '/' + i;
    }
    s += '\n';
  }
  return s;
}

std::string writeOff(const MeshBuffers& mesh) {
  std::string s = "OFF\n" + std::to_string(mesh.vertexCount()) + ' ' + std::to_string(mesh.triangleCount()) + " 0\n";
  for (size_t v = 0; v < mesh.vertexCount(); ++v) {
    appendXYZ(s, &mesh.positions[3 * v]);
    s += '\n';
  }
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    s += "3 " + std::to_string(mesh.triangles[3 * t]) + ' ' + std::to_string(mesh.triangles[3 * t + 1]) + ' ' +
         std::to_string(mesh.triangles[3 * t + 2]) + '\n';
  return s;
}

// Unit normal of triangle t (zero for a degenerate triangle).
void normalOf(const MeshBuffers& mesh, size_t t, double n[3]) {
  const double* a = &mesh.positions[3 * size_t(mesh.triangles[3 * t])];
  const double* b = &mesh.positions[3 * size_t(mesh.triangles[3 * t + 1])];
  const double* c = &mesh.positions[3 * size_t(mesh.triangles[3 * t + 2])];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int k = 0; k < 3; ++k) n[k] = (len > 0 && std::isfinite(len)) ? n[k] / len : 0.0;
}

std::string writeStlAscii(const MeshBuffers& mesh) {
  std::string s = "solid conformesh\n";
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    double n[3];
    normalOf(mesh, t, n);
    s += "facet normal ";
    appendXYZ(s, n);
    s += "\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      s += "    vertex ";
      appendXYZ(s, &mesh.positions[3 * size_t(mesh.triangles[3 * t + k])]);
      s += '\n';
    }
    s += "  endloop\nendfacet\n";
  }
  s += "endsolid conformesh\n";
  return s;
}

void putLE32(uint8_t* p, uint32_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
  p[2] = uint8_t(v >> 16);
  p[3] = uint8_t(v >> 24);
}

void putFloatLE(uint8_t* p, double v) {
  float f = float(v);
  uint32_t b;
  std::memcpy(&b, &f, 4);
  putLE32(p, b);
}

std::vector<uint8_t> writeStlBinary(const MeshBuffers& mesh) {
  const size_t nt = mesh.triangleCount();
  if (uint64_t(nt) > 0xFFFFFFFFull) fail(Code::TooLarge, Stage::Write, "binary STL holds at most 2^32 - 1 triangles");
  std::vector<uint8_t> out(84 + 50 * nt, 0);
  const char header[] = "binary STL written by conformesh";
  std::memcpy(out.data(), header, sizeof(header) - 1);  // not "solid": readers must not take it for ascii
  putLE32(&out[80], uint32_t(nt));
  for (size_t t = 0; t < nt; ++t) {
    uint8_t* r = &out[84 + 50 * t];
    double n[3];
    normalOf(mesh, t, n);
    for (int k = 0; k < 3; ++k) putFloatLE(r + 4 * k, n[k]);
    for (int c = 0; c < 3; ++c) {
      const double* p = &mesh.positions[3 * size_t(mesh.triangles[3 * t + c])];
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(float(p[k])))
          fail(Code::NonFiniteCoordinate, Stage::Write, "coordinate overflows a 32-bit float in binary STL");
        putFloatLE(r + 12 + 12 * c + 4 * k, p[k]);
      }
    }
  }
  return out;
}

std::vector<uint8_t> writePly(const MeshBuffers& mesh, MeshFormat format, bool uvs) {
  const char* enc = format == MeshFormat::PlyAscii      ? "ascii"
                    : format == MeshFormat::PlyBinaryBE ? "binary_big_endian"
                                                        : "binary_little_endian";
  std::string h = std::string("ply\nformat ") + enc + " 1.0\ncomment written by conformesh\n";
  h += "element vertex " + std::to_string(mesh.vertexCount()) + "\n";
  h += "property double x\nproperty double y\nproperty double z\n";
  if (uvs) h += "property double u\nproperty double v\n";
  h += "element face " + std::to_string(mesh.triangleCount()) + "\n";
  h += "property list uchar uint vertex_indices\nend_header\n";
  const size_t nv = mesh.vertexCount(), nt = mesh.triangleCount();
  if (format == MeshFormat::PlyAscii) {
    for (size_t v = 0; v < nv; ++v) {
      appendXYZ(h, &mesh.positions[3 * v]);
      if (uvs) {
        h += ' ';
        appendDouble(h, mesh.uvs[2 * v]);
        h += ' ';
        appendDouble(h, mesh.uvs[2 * v + 1]);
      }
      h += '\n';
    }
    for (size_t t = 0; t < nt; ++t)
      h += "3 " + std::to_string(mesh.triangles[3 * t]) + ' ' + std::to_string(mesh.triangles[3 * t + 1]) + ' ' +
           std::to_string(mesh.triangles[3 * t + 2]) + '\n';
    return toBytes(h);
  }
  const bool be = format == MeshFormat::PlyBinaryBE;
  const size_t perVertex = uvs ? 5 : 3;
  std::vector<uint8_t> out(h.begin(), h.end());
  const size_t body = out.size();
  out.resize(body + nv * perVertex * 8 + nt * 13);
  uint8_t* q = out.data() + body;
  auto put = [&](const void* src, size_t n) {
    const uint8_t* s = static_cast<const uint8_t*>(src);
    for (size_t i = 0; i < n; ++i) q[i] = be ? s[n - 1 - i] : s[i];  // hosts are little endian
    q += n;
  };
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) put(&mesh.positions[3 * v + k], 8);
    if (uvs)
      for (int k = 0; k < 2; ++k) put(&mesh.uvs[2 * v + k], 8);
  }
  for (size_t t = 0; t < nt; ++t) {
    *q++ = 3;
    for (int k = 0; k < 3; ++k) put(&mesh.triangles[3 * t + k], 4);
  }
  return out;
}

}  // namespace

std::vector<uint8_t> writeMesh(const MeshBuffers& mesh, MeshFormat format, const WriteOptions& options) {
  checkBuffers(mesh);
  const bool uvs = options.writeUvs && !mesh.uvs.empty();
  switch (format) {
    case MeshFormat::Obj: return toBytes(writeObj(mesh, uvs));
    case MeshFormat::Off: return toBytes(writeOff(mesh));
    case MeshFormat::StlAscii: return toBytes(writeStlAscii(mesh));
    case MeshFormat::StlBinary: return writeStlBinary(mesh);
    case MeshFormat::PlyAscii:
    case MeshFormat::PlyBinaryLE:
    case MeshFormat::PlyBinaryBE: return writePly(mesh, format, uvs);
    case MeshFormat::Auto: break;
  }
  fail(Code::InvalidArgument, Stage::Write, "writeMesh needs a concrete format, not auto");
}

}  // namespace conformesh
