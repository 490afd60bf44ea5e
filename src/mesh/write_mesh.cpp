// conformesh — mesh writers: OBJ (optional vt, vn), OFF, STL ascii and binary, PLY ascii and
// binary (little or big endian, double coordinates, uint32 indices, attributes as properties).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/io_detail.h"
#include "mesh/mesh_attributes.h"

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
  checkAttributes(mesh, Stage::Write);
}

const MeshAttribute* findAttribute(const MeshBuffers& mesh, const char* name, uint32_t components) {
  for (const MeshAttribute& a : mesh.attributes)
    if (a.name == name && a.components == components) return &a;
  return nullptr;
}

// An OBJ index list (vt or vn) for an attribute: per vertex, item v is vertex v; per corner,
// equal values share one entry, numbered by first appearance.
struct ObjIndexedValues {
  std::vector<double> values;  // k per entry
  std::vector<uint32_t> cornerIndex;  // per corner, its entry
};
ObjIndexedValues objIndexed(const MeshBuffers& mesh, const std::vector<double>& values, uint32_t k, bool perCorner) {
  ObjIndexedValues out;
  out.cornerIndex.resize(mesh.triangles.size());
  if (!perCorner) {
    out.values = values;
    out.cornerIndex = mesh.triangles;
    return out;
  }
  std::unordered_map<std::string, uint32_t> index;  // the values' bytes -> entry
  for (size_t c = 0; c < mesh.triangles.size(); ++c) {
    const double* v = &values[c * k];
    std::string key(reinterpret_cast<const char*>(v), k * sizeof(double));
    auto it = index.emplace(std::move(key), uint32_t(out.values.size() / k)).first;
    if (it->second == out.values.size() / k) out.values.insert(out.values.end(), v, v + k);
    out.cornerIndex[c] = it->second;
  }
  return out;
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

std::vector<uint8_t> writeObj(const MeshBuffers& mesh, bool uvs, bool attributes) {
  // texture coordinates: per vertex (mesh.uvs) or per corner (the attribute "uv"); normals: the
  // attribute "normal", either way
  const MeshAttribute* cornerUv = uvs && mesh.uvs.empty() ? findAttribute(mesh, "uv", 2) : nullptr;
  const MeshAttribute* normal = attributes ? findAttribute(mesh, "normal", 3) : nullptr;
  ObjIndexedValues vt, vn;
  const bool hasVt = uvs && (!mesh.uvs.empty() || cornerUv), hasVn = normal != nullptr;
  if (hasVt) vt = cornerUv ? objIndexed(mesh, cornerUv->values, 2, true) : objIndexed(mesh, mesh.uvs, 2, false);
  if (hasVn) vn = objIndexed(mesh, normal->values, 3, normal->perCorner);
  TextOut s(mesh.vertexCount() * (hasVt ? 100 : 60) + mesh.triangleCount() * (hasVt ? 50 : 30) + 64);
  s += "# conformesh\n";
  const size_t nv = mesh.vertexCount();
  for (size_t v = 0; v < nv; ++v) {
    s += "v ";
    appendXYZ(s, &mesh.positions[3 * v]);
    s += '\n';
  }
  for (size_t i = 0; i < vt.values.size(); i += 2) {
    s += "vt ";
    appendDouble(s, vt.values[i]);
    s += ' ';
    appendDouble(s, vt.values[i + 1]);
    s += '\n';
  }
  for (size_t i = 0; i < vn.values.size(); i += 3) {
    s += "vn ";
    appendXYZ(s, &vn.values[i]);
    s += '\n';
  }
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    s += 'f';
    for (size_t c = 3 * t; c < 3 * t + 3; ++c) {
      s += ' ';
      appendUInt(s, mesh.triangles[c] + uint64_t(1));
      if (hasVt || hasVn) s += '/';
      if (hasVt) appendUInt(s, vt.cornerIndex[c] + uint64_t(1));
      if (hasVn) {
        s += '/';
        appendUInt(s, vn.cornerIndex[c] + uint64_t(1));
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

// One scalar PLY property: values[stride · item + offset], written as a double, or as a uchar
// (colours: 255 · the value clamped to [0, 1], rounded).
struct PlyColumn {
  std::string name;
  const std::vector<double>* values;
  uint32_t stride, offset;
  bool uchar;
};

// The vertex properties after x y z: u v, then the per-vertex attributes ("normal" as nx ny nz,
// "color" as uchar red green blue [alpha], a 1-component one by its name, others name_0, ...).
std::vector<PlyColumn> plyVertexColumns(const MeshBuffers& mesh, bool uvs, bool attributes) {
  std::vector<PlyColumn> cols;
  if (uvs && !mesh.uvs.empty())
    for (uint32_t k = 0; k < 2; ++k) cols.push_back({k ? "v" : "u", &mesh.uvs, 2, k, false});
  for (const MeshAttribute& a : mesh.attributes) {
    if (a.perCorner || !attributes) continue;
    static const char* const kNormal[] = {"nx", "ny", "nz"};
    static const char* const kColor[] = {"red", "green", "blue", "alpha"};
    const bool normal = a.name == "normal" && a.components == 3;
    const bool color = a.name == "color" && (a.components == 3 || a.components == 4);
    for (uint32_t k = 0; k < a.components; ++k) {
      std::string name = normal ? kNormal[k] : color ? kColor[k] : a.components == 1 ? a.name : a.name + "_" + std::to_string(k);
      cols.push_back({std::move(name), &a.values, a.components, k, color});
    }
  }
  return cols;
}

uint8_t colorByte(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

std::vector<uint8_t> writePly(const MeshBuffers& mesh, MeshFormat format, bool uvs, bool attributes) {
  const char* enc = format == MeshFormat::PlyAscii      ? "ascii"
                    : format == MeshFormat::PlyBinaryBE ? "binary_big_endian"
                                                        : "binary_little_endian";
  const std::vector<PlyColumn> cols = plyVertexColumns(mesh, uvs, attributes);
  // per-corner attributes: a list per face, 3 · components values ("uv" as MeshLab's texcoord)
  std::vector<const MeshAttribute*> faceLists;
  for (const MeshAttribute& a : mesh.attributes)
    if (a.perCorner && 3 * a.components <= 255 && (a.name == "uv" ? uvs : attributes)) faceLists.push_back(&a);
  auto listName = [](const MeshAttribute& a) { return a.name == "uv" ? std::string("texcoord") : a.name; };
  std::string h = std::string("ply\nformat ") + enc + " 1.0\ncomment written by conformesh\n";
  h += "element vertex " + std::to_string(mesh.vertexCount()) + "\n";
  h += "property double x\nproperty double y\nproperty double z\n";
  for (const PlyColumn& c : cols) h += std::string("property ") + (c.uchar ? "uchar " : "double ") + c.name + "\n";
  h += "element face " + std::to_string(mesh.triangleCount()) + "\n";
  h += "property list uchar uint vertex_indices\n";
  for (const MeshAttribute* a : faceLists) h += "property list uchar double " + listName(*a) + "\n";
  h += "end_header\n";
  const size_t nv = mesh.vertexCount(), nt = mesh.triangleCount();
  if (format == MeshFormat::PlyAscii) {
    TextOut s(h.size() + nv * (60 + 20 * cols.size()) + nt * 30);
    s += h;
    for (size_t v = 0; v < nv; ++v) {
      appendXYZ(s, &mesh.positions[3 * v]);
      for (const PlyColumn& c : cols) {
        s += ' ';
        const double x = (*c.values)[c.stride * v + c.offset];
        if (c.uchar) appendUInt(s, colorByte(x));
        else appendDouble(s, x);
      }
      s += '\n';
    }
    for (size_t t = 0; t < nt; ++t) {
      if (faceLists.empty()) {
        appendFace3(s, &mesh.triangles[3 * t]);
        continue;
      }
      s += '3';
      for (int k = 0; k < 3; ++k) {
        s += ' ';
        appendUInt(s, mesh.triangles[3 * t + k]);
      }
      for (const MeshAttribute* a : faceLists) {
        s += ' ';
        appendUInt(s, 3 * a->components);
        for (size_t i = 3 * t * a->components; i < 3 * (t + 1) * a->components; ++i) {
          s += ' ';
          appendDouble(s, a->values[i]);
        }
      }
      s += '\n';
    }
    return s.take();
  }
  const bool be = format == MeshFormat::PlyBinaryBE;
  size_t perVertex = 24, perFace = 13;
  for (const PlyColumn& c : cols) perVertex += c.uchar ? 1 : 8;
  for (const MeshAttribute* a : faceLists) perFace += 1 + 24 * size_t(a->components);
  std::vector<uint8_t> out(h.begin(), h.end());
  const size_t body = out.size();
  if (nv > (SIZE_MAX / 2 - body) / perVertex || nt > (SIZE_MAX / 2) / perFace)
    fail(Code::TooLarge, Stage::Write, "PLY would not fit in memory");
  out.resize(body + nv * perVertex + nt * perFace);
  uint8_t* q = out.data() + body;
  auto put = [&](const void* src, size_t n) {
    const uint8_t* s = static_cast<const uint8_t*>(src);
    for (size_t i = 0; i < n; ++i) q[i] = be ? s[n - 1 - i] : s[i];  // hosts are little endian
    q += n;
  };
  for (size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) put(&mesh.positions[3 * v + k], 8);
    for (const PlyColumn& c : cols) {
      const double& x = (*c.values)[c.stride * v + c.offset];
      if (c.uchar) *q++ = colorByte(x);
      else put(&x, 8);
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    *q++ = 3;
    for (int k = 0; k < 3; ++k) put(&mesh.triangles[3 * t + k], 4);
    for (const MeshAttribute* a : faceLists) {
      *q++ = uint8_t(3 * a->components);
      for (size_t i = 3 * t * a->components; i < 3 * (t + 1) * a->components; ++i) put(&a->values[i], 8);
    }
  }
  return out;
}

}  // namespace

std::vector<uint8_t> writeMesh(const MeshBuffers& mesh, MeshFormat format, const WriteOptions& options) {
  checkBuffers(mesh);
  const bool uvs = options.writeUvs, attributes = options.writeAttributes;
  switch (format) {
    case MeshFormat::Obj: return writeObj(mesh, uvs, attributes);
    case MeshFormat::Off: return writeOff(mesh);
    case MeshFormat::StlAscii: return writeStlAscii(mesh);
    case MeshFormat::StlBinary: return writeStlBinary(mesh);
    case MeshFormat::PlyAscii:
    case MeshFormat::PlyBinaryLE:
    case MeshFormat::PlyBinaryBE: return writePly(mesh, format, uvs, attributes);
    case MeshFormat::Auto: break;
  }
  fail(Code::InvalidArgument, Stage::Write, "writeMesh needs a concrete format, not auto");
}

}  // namespace conformesh
