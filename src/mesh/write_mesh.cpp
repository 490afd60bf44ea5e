// conformesh — mesh writers: OBJ (optional vt), OFF, STL ascii and binary, PLY ascii and binary
// (little or big endian, double coordinates, uint32 indices).
#include <algorithm>
#include <cmath>
#include <cstdint>
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

// Text output straight into the byte vector writeMesh returns.
class TextOut {
 public:
  explicit TextOut(size_t reserve) : bytes_(reserve) {}
  void append(const char* s, size_t k) {
    if (n_ + k > bytes_.size()) bytes_.resize(std::max(2 * bytes_.size(), n_ + k + 4096));
    std::memcpy(bytes_.data() + n_, s, k);
    n_ += k;
  }
  TextOut& operator+=(char c) {
    append(&c, 1);
    return *this;
  }
  TextOut& operator+=(const char* s) {
    append(s, std::strlen(s));
    return *this;
  }
  TextOut& operator+=(const std::string& s) {
    append(s.data(), s.size());
    return *this;
  }
  std::vector<uint8_t> take() {
    bytes_.resize(n_);
    return std::move(bytes_);
  }

 private:
  std::vector<uint8_t> bytes_;
  size_t n_ = 0;
};

void appendDouble(TextOut& out, double v) {
  char buf[kMaxDoubleChars];
  out.append(buf, formatDouble(v, buf));
}

void appendUInt(TextOut& out, uint64_t v) {
  char buf[24];
  char* e = buf + sizeof(buf);
  char* b = e;
  do {
    *--b = char('0' + v % 10);
    v /= 10;
  } while (v);
  out.append(b, size_t(e - b));
}

// "3 a b c\n" (OFF, ascii PLY face lines).
void appendFace3(TextOut& out, const uint32_t* t) {
  out += '3';
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    appendUInt(out, t[k]);
  }
  out += '\n';
}

void appendXYZ(TextOut& out, const double* p) {
  appendDouble(out, p[0]);
  out += ' ';
  appendDouble(out, p[1]);
  out += ' ';
  appendDouble(out, p[2]);
}

std::vector<uint8_t> writeObj(const MeshBuffers& mesh, bool uvs) {
  TextOut s(mesh.vertexCount() * (uvs ? 100 : 60) + mesh.triangleCount() * (uvs ? 50 : 30) + 64);
  s += "# conformesh\n";
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
      const uint64_t i = mesh.triangles[3 * t + k] + uint64_t(1);
      s += ' ';
      appendUInt(s, i);
      if (uvs) {
        s += '/';
        appendUInt(s, i);
      }
    }
    s += '\n';
  }
  return s.take();
}

std::vector<uint8_t> writeOff(const MeshBuffers& mesh) {
  TextOut s(mesh.vertexCount() * 60 + mesh.triangleCount() * 30 + 64);
  s += "OFF\n" + std::to_string(mesh.vertexCount()) + ' ' + std::to_string(mesh.triangleCount()) + " 0\n";
  for (size_t v = 0; v < mesh.vertexCount(); ++v) {
    appendXYZ(s, &mesh.positions[3 * v]);
    s += '\n';
  }
  for (size_t t = 0; t < mesh.triangleCount(); ++t) appendFace3(s, &mesh.triangles[3 * t]);
  return s.take();
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

std::vector<uint8_t> writeStlAscii(const MeshBuffers& mesh) {
  TextOut s(mesh.triangleCount() * 300 + 64);
  s += "solid conformesh\n";
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
  return s.take();
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
  if (nt > (SIZE_MAX - 84) / 50) fail(Code::TooLarge, Stage::Write, "binary STL would not fit in memory");
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
    TextOut s(h.size() + nv * (uvs ? 100 : 60) + nt * 30);
    s += h;
    for (size_t v = 0; v < nv; ++v) {
      appendXYZ(s, &mesh.positions[3 * v]);
      if (uvs) {
        s += ' ';
        appendDouble(s, mesh.uvs[2 * v]);
        s += ' ';
        appendDouble(s, mesh.uvs[2 * v + 1]);
      }
      s += '\n';
    }
    for (size_t t = 0; t < nt; ++t) appendFace3(s, &mesh.triangles[3 * t]);
    return s.take();
  }
  const bool be = format == MeshFormat::PlyBinaryBE;
  const size_t perVertex = uvs ? 5 : 3;
  std::vector<uint8_t> out(h.begin(), h.end());
  const size_t body = out.size();
  if (nv > (SIZE_MAX / 2 - body) / (perVertex * 8) || nt > (SIZE_MAX / 2) / 13)
    fail(Code::TooLarge, Stage::Write, "PLY would not fit in memory");
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
    case MeshFormat::Obj: return writeObj(mesh, uvs);
    case MeshFormat::Off: return writeOff(mesh);
    case MeshFormat::StlAscii: return writeStlAscii(mesh);
    case MeshFormat::StlBinary: return writeStlBinary(mesh);
    case MeshFormat::PlyAscii:
    case MeshFormat::PlyBinaryLE:
    case MeshFormat::PlyBinaryBE: return writePly(mesh, format, uvs);
    case MeshFormat::Auto: break;
  }
  fail(Code::InvalidArgument, Stage::Write, "writeMesh needs a concrete format, not auto");
}

}  // namespace conformesh
