// conformesh — PLY reader (Turk 1994 format): ascii, binary_little_endian, binary_big_endian.
// Vertex positions from the "vertex" element's x, y, z properties (any scalar type, anywhere
// among other properties); faces from the "face" element's list property "vertex_indices" or
// "vertex_index" (any integer count and item types); optional uvs from u/v, s/t or
// texture_u/texture_v; with ReadOptions::readAttributes the vertex element's other scalar
// properties as mesh.attributes (colours, normals, any other value: mesh_io.h). Other elements and
// list properties are skipped; comment and obj_info lines are ignored.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mesh/io_detail.h"

namespace conformesh::io_detail {

namespace {

enum class PType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, Invalid };

PType parseType(const std::string& s) {
  if (s == "char" || s == "int8") return PType::Int8;
  if (s == "uchar" || s == "uint8") return PType::UInt8;
  if (s == "short" || s == "int16") return PType::Int16;
  if (s == "ushort" || s == "uint16") return PType::UInt16;
  if (s == "int" || s == "int32") return PType::Int32;
  if (s == "uint" || s == "uint32") return PType::UInt32;
  if (s == "float" || s == "float32") return PType::Float32;
  if (s == "double" || s == "float64") return PType::Float64;
  return PType::Invalid;
}

size_t typeSize(PType t) {
  switch (t) {
    case PType::Int8:
    case PType::UInt8: return 1;
    case PType::Int16:
    case PType::UInt16: return 2;
    case PType::Int32:
    case PType::UInt32:
    case PType::Float32: return 4;
    case PType::Float64: return 8;
    case PType::Invalid: return 0;
  }
  return 0;
}

bool isIntegerType(PType t) { return t != PType::Float32 && t != PType::Float64; }

enum Role { kNone = -1, kX = 0, kY = 1, kZ = 2, kU = 3, kV = 4, kFace = 5, kAttribute = 6, kTexcoord = 7 };

struct Property {
  std::string name;
  PType type = PType::Invalid;  // item type for lists
  bool list = false;
  PType countType = PType::Invalid;
  int role = kNone;
  // kAttribute: the value goes to component `component` of mesh.attributes[attribute], times scale
  uint32_t attribute = 0, component = 0;
  double scale = 1.0;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
  size_t headerLine = 0;
};

// The value of a T stored (host byte order) at b, as double.
template <class T>
double loadAs(const uint8_t* b) {
  T v;
  std::memcpy(&v, b, sizeof v);
  return double(v);
}

// Load a scalar of type t from p (little-endian file unless bigEndian) as double.
double loadScalar(const uint8_t* p, PType t, bool bigEndian) {
  uint8_t b[8];
  const size_t n = typeSize(t);
  for (size_t i = 0; i < n; ++i) b[i] = bigEndian ? p[n - 1 - i] : p[i];
  switch (t) {
    case PType::Int8: return loadAs<int8_t>(b);
    case PType::UInt8: return loadAs<uint8_t>(b);
    case PType::Int16: return loadAs<int16_t>(b);
    case PType::UInt16: return loadAs<uint16_t>(b);
    case PType::Int32: return loadAs<int32_t>(b);
    case PType::UInt32: return loadAs<uint32_t>(b);
    case PType::Float32: return loadAs<float>(b);
    case PType::Float64: return loadAs<double>(b);
    case PType::Invalid: break;
  }
  return 0.0;
}

// Header tokenizer over one line.
std::vector<std::string> splitWords(const char* b, const char* e) {
  std::vector<std::string> w;
  TextScanner sc(b, e, '\0');
  const char *tb, *te;
  while (sc.next(tb, te)) w.emplace_back(tb, te);
  return w;
}

// The vertex element's properties that are not positions or uvs, as attributes of `mesh`
// (mesh_io.h, ReadOptions::readAttributes): colours and normals grouped when all their
// components are there, every other scalar its own 1-component attribute.
void assignAttributes(std::vector<Property>& props, MeshBuffers& mesh, uint64_t nv, bool readUvs) {
  auto isUvName = [](const std::string& n) {
    return n == "u" || n == "v" || n == "s" || n == "t" || n.rfind("texture_", 0) == 0;
  };
  auto find = [&](const std::string& n) -> Property* {
    for (Property& pr : props)
      if (!pr.list && pr.role == kNone && pr.name == n) return &pr;
    return nullptr;
  };
  auto group = [&](const char* name, std::vector<std::string> names, size_t required, bool colour) {
    std::vector<Property*> found;
    for (const std::string& n : names) {
      Property* pr = find(n);
      if (!pr) break;
      found.push_back(pr);
    }
    if (found.size() < required) return;
    for (uint32_t c = 0; c < found.size(); ++c) {
      Property& pr = *found[c];
      pr.role = kAttribute;
      pr.attribute = uint32_t(mesh.attributes.size());
      pr.component = c;
      if (colour) pr.scale = pr.type == PType::UInt8 ? 1.0 / 255 : pr.type == PType::UInt16 ? 1.0 / 65535 : 1.0;
    }
    mesh.attributes.push_back(MeshAttribute{name, uint32_t(found.size()), false, {}});
  };
  group("color", {"red", "green", "blue", "alpha"}, 3, true);
  group("color", {"diffuse_red", "diffuse_green", "diffuse_blue", "diffuse_alpha"}, 3, true);
  group("normal", {"nx", "ny", "nz"}, 3, false);
  for (Property& pr : props)
    if (!pr.list && pr.role == kNone && (readUvs || !isUvName(pr.name))) {
      pr.role = kAttribute;
      pr.attribute = uint32_t(mesh.attributes.size());
      mesh.attributes.push_back(MeshAttribute{pr.name, 1, false, {}});
    }
  for (MeshAttribute& a : mesh.attributes) a.values.assign(size_t(nv) * a.components, 0.0);
}

// Store vertex i's value v of a property with a role (position, uv or attribute).
void storeVertexValue(const Property& pr, uint64_t i, double v, MeshBuffers& mesh, bool uvs) {
  if (pr.role <= kZ) mesh.positions[3 * size_t(i) + pr.role] = v;
  else if (pr.role == kAttribute) {
    MeshAttribute& a = mesh.attributes[pr.attribute];
    a.values[size_t(i) * a.components + pr.component] = v * pr.scale;
  } else if (uvs) mesh.uvs[2 * size_t(i) + (pr.role - kU)] = v;
}

struct FaceSink {
  FaceSink(MeshBuffers& m, uint64_t n) : mesh(m), nv(n) {}
  MeshBuffers& mesh;
  uint64_t nv;
  // Adds polygon corners one by one, fan-triangulating.
  int64_t first = 0, prev = 0;
  size_t corner = 0;
  // the face's texcoord list (u v per polygon corner), and the uv of every triangle corner so far
  std::vector<double> polyUv, cornerUv;
  bool uvsComplete = true;
  void begin() { corner = 0; }
  //! After every face: its texcoord values to its triangles' corners (fan 0, i, i + 1).
  void endFace() {
    if (polyUv.size() != 2 * corner) uvsComplete = false;
    else
      for (size_t i = 1; i + 1 < corner; ++i)
        for (size_t c : {size_t(0), i, i + 1}) cornerUv.insert(cornerUv.end(), {polyUv[2 * c], polyUv[2 * c + 1]});
    polyUv.clear();
  }
  bool add(int64_t idx) {  // false: out of range
    if (idx < 0 || uint64_t(idx) >= nv) return false;
    if (corner == 0) {
      first = idx;
    } else if (corner >= 2) {
      mesh.triangles.push_back(uint32_t(first));
      mesh.triangles.push_back(uint32_t(prev));
      mesh.triangles.push_back(uint32_t(idx));
    }
    prev = idx;
    ++corner;
    return true;
  }
};

}  // namespace

void readPly(const Source& src, const ReadOptions& opt, ReadResult& result) {
  const char* text = reinterpret_cast<const char*>(src.data);
  const char* const end = text + src.size;
  const char* p = text;
  size_t line = 0;
  enum { kAscii, kLE, kBE, kUnknown } encoding = kUnknown;
  std::vector<Element> elements;
  bool ended = false;
  while (p < end && !ended) {
    ++line;
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    if (!nl) src.failLine(Code::ParseError, line, "PLY header not terminated by 'end_header'");
    std::vector<std::string> w = splitWords(p, nl);
    p = nl + 1;
    if (line == 1) {
      if (w.size() != 1 || w[0] != "ply") src.failLine(Code::ParseError, line, "PLY must start with 'ply'");
      continue;
    }
    if (w.empty()) continue;
    const std::string& k = w[0];
    if (k == "comment" || k == "obj_info") continue;
    if (k == "format") {
      if (w.size() < 2) src.failLine(Code::ParseError, line, "bad format line");
      if (w[1] == "ascii") encoding = kAscii;
      else if (w[1] == "binary_little_endian") encoding = kLE;
      else if (w[1] == "binary_big_endian") encoding = kBE;
      else src.failLine(Code::ParseError, line, "unknown PLY format '" + w[1] + "'");
    } else if (k == "element") {
      int64_t count;
      if (w.size() != 3 || !parseInt(w[2].data(), w[2].data() + w[2].size(), count) || count < 0)
        src.failLine(Code::ParseError, line, "bad element line (expected 'element <name> <count>')");
      Element el;
      el.name = w[1];
      el.count = uint64_t(count);
      el.headerLine = line;
      elements.push_back(std::move(el));
    } else if (k == "property") {
      if (elements.empty()) src.failLine(Code::ParseError, line, "property before any element");
      Property pr;
      if (w.size() == 5 && w[1] == "list") {
        pr.list = true;
        pr.countType = parseType(w[2]);
        pr.type = parseType(w[3]);
        pr.name = w[4];
        if (pr.countType == PType::Invalid || pr.type == PType::Invalid || !isIntegerType(pr.countType))
          src.failLine(Code::ParseError, line, "bad list property types");
      } else if (w.size() == 3) {
        pr.type = parseType(w[1]);
        pr.name = w[2];
        if (pr.type == PType::Invalid) src.failLine(Code::ParseError, line, "unknown property type '" + w[1] + "'");
      } else {
        src.failLine(Code::ParseError, line, "bad property line");
      }
      elements.back().props.push_back(std::move(pr));
    } else if (k == "end_header") {
      ended = true;
    } else {
      src.failLine(Code::ParseError, line, "unexpected PLY header line '" + k.substr(0, 40) + "'");
    }
  }
  if (!ended) src.failLine(Code::ParseError, line, "PLY header not terminated by 'end_header'");
  if (encoding == kUnknown) src.failPlain(Code::ParseError, "PLY header has no format line");
  result.format = encoding == kAscii ? MeshFormat::PlyAscii : encoding == kLE ? MeshFormat::PlyBinaryLE
                                                                            : MeshFormat::PlyBinaryBE;
  const bool binary = encoding != kAscii;
  const bool bigEndian = encoding == kBE;

  // Roles, and the element counts checked against the bytes before anything is allocated.
  Element* vertexEl = nullptr;
  const Element* faceEl = nullptr;
  bool hasU = false, hasV = false, texcoords = false;
  uint64_t remaining = uint64_t(end - p);
  for (Element& el : elements) {
    uint64_t minBytes = 0;
    for (Property& pr : el.props) {
      if (binary) minBytes += pr.list ? typeSize(pr.countType) : typeSize(pr.type);
      else minBytes += 2;
    }
    if (minBytes > 0 && el.count > (remaining + (binary ? 0 : 1)) / minBytes)
      src.failLine(Code::TooLarge, el.headerLine,
                   "element '" + el.name + "' claims " + std::to_string(el.count) + " items, more than the " +
                       std::to_string(remaining) + " bytes after the header can hold");
    remaining -= std::min(remaining, el.count * minBytes);
    if (el.name == "vertex" && !vertexEl) {
      vertexEl = &el;
      for (Property& pr : el.props) {
        if (pr.list) continue;
        const std::string& n = pr.name;
        if (n == "x") pr.role = kX;
        else if (n == "y") pr.role = kY;
        else if (n == "z") pr.role = kZ;
        else if (opt.readUvs && (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")) pr.role = kU, hasU = true;
        else if (opt.readUvs && (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")) pr.role = kV, hasV = true;
      }
    } else if (el.name == "face" && !faceEl) {
      faceEl = &el;
      for (Property& pr : el.props)
        if (pr.list && (pr.name == "vertex_indices" || pr.name == "vertex_index") && isIntegerType(pr.type)) {
          pr.role = kFace;
          break;
        }
      // per-corner texture coordinates (MeshLab's texcoord list) when there are no per-vertex ones
      for (Property& pr : el.props)
        if (pr.list && pr.name == "texcoord" && !isIntegerType(pr.type) && opt.readUvs && !(hasU && hasV)) {
          pr.role = kTexcoord;
          texcoords = true;
        }
    }
  }
  if (!vertexEl) src.failPlain(Code::EmptyMesh, "PLY has no 'vertex' element");
  int found = 0;
  for (const Property& pr : vertexEl->props)
    if (pr.role >= kX && pr.role <= kZ) found |= 1 << pr.role;
  if (found != 7) src.failLine(Code::ParseError, vertexEl->headerLine, "PLY vertex element lacks x, y or z");
  if (vertexEl->count > kMaxVertices) src.failPlain(Code::TooLarge, "too many vertices");
  if (!faceEl) src.failPlain(Code::EmptyMesh, "PLY has no 'face' element");
  bool faceProp = false;
  for (const Property& pr : faceEl->props) faceProp |= pr.role == kFace;
  if (!faceProp) src.failLine(Code::ParseError, faceEl->headerLine, "PLY face element lacks a vertex_indices list");

  MeshBuffers& mesh = result.mesh;
  const uint64_t nv = vertexEl->count;
  mesh.positions.assign(size_t(nv) * 3, 0.0);
  const bool uvs = hasU && hasV;
  if (uvs) mesh.uvs.assign(size_t(nv) * 2, 0.0);
  if (opt.readAttributes) assignAttributes(vertexEl->props, mesh, nv, opt.readUvs);
  FaceSink sink(mesh, nv);

  if (binary) {
    const uint8_t* q = reinterpret_cast<const uint8_t*>(p);
    const uint8_t* const qend = src.data + src.size;
    auto need = [&](uint64_t n, const char* what) {
      if (uint64_t(qend - q) < n)
        src.failOffset(Code::ParseError, uint64_t(q - src.data), std::string("PLY data truncated in ") + what);
    };
    for (const Element& el : elements) {
      if (el.props.empty()) continue;  // nothing to read, whatever its count
      const bool isVertex = &el == vertexEl, isFace = &el == faceEl;
      for (uint64_t i = 0; i < el.count; ++i) {
        for (const Property& pr : el.props) {
          if (!pr.list) {
            const size_t sz = typeSize(pr.type);
            need(sz, el.name.c_str());
            if (isVertex && pr.role != kNone) {
              double v = loadScalar(q, pr.type, bigEndian);
              if (!std::isfinite(v) && pr.role != kAttribute)
                src.failOffset(Code::NonFiniteCoordinate, uint64_t(q - src.data), "non-finite vertex value");
              storeVertexValue(pr, i, v, mesh, uvs);
            }
            q += sz;
            continue;
          }
          const size_t csz = typeSize(pr.countType), isz = typeSize(pr.type);
          need(csz, el.name.c_str());
          const uint64_t listOffset = uint64_t(q - src.data);
          const double c = loadScalar(q, pr.countType, bigEndian);
          q += csz;
          if (c < 0) src.failOffset(Code::ParseError, listOffset, "negative list length");
          const uint64_t n = uint64_t(c);
          need(n * isz, el.name.c_str());
          if (isFace && pr.role == kFace) {
            if (n < 3) src.failOffset(Code::ParseError, listOffset, "face with " + std::to_string(n) + " < 3 vertices");
            sink.begin();
            for (uint64_t j = 0; j < n; ++j, q += isz) {
              const double idx = loadScalar(q, pr.type, bigEndian);
              if (!sink.add(int64_t(idx)))
                src.failOffset(Code::IndexOutOfRange, uint64_t(q - src.data),
                               "vertex index " + std::to_string(int64_t(idx)) + " not in [0, " + std::to_string(nv) + ")");
            }
          } else if (isFace && pr.role == kTexcoord) {
            for (uint64_t j = 0; j < n; ++j, q += isz) sink.polyUv.push_back(loadScalar(q, pr.type, bigEndian));
          } else {
            q += n * isz;
          }
        }
        if (isFace && texcoords) sink.endFace();
      }
    }
    if (q != qend)
      result.warnings.push_back(std::to_string(qend - q) + " bytes after the PLY data ignored");
  } else {
    TextScanner sc(p, end, '\0', line + 1);
    const char *b, *e;
    auto nextToken = [&](const char* what) {
      if (!sc.next(b, e))
        src.failLine(Code::ParseError, sc.line(), std::string("end of file in PLY element '") + what + "'");
    };
    for (const Element& el : elements) {
      if (el.props.empty()) continue;  // nothing to read, whatever its count
      const bool isVertex = &el == vertexEl, isFace = &el == faceEl;
      for (uint64_t i = 0; i < el.count; ++i) {
        for (const Property& pr : el.props) {
          if (!pr.list) {
            nextToken(el.name.c_str());
            if (isVertex && pr.role != kNone) {
              double v;
              if (!parseDouble(b, e, v))
                src.failLine(Code::ParseError, sc.tokenLine(), "bad number '" + std::string(b, e) + "'");
              if (!std::isfinite(v) && pr.role != kAttribute)
                src.failLine(Code::NonFiniteCoordinate, sc.tokenLine(), "non-finite vertex value");
              storeVertexValue(pr, i, v, mesh, uvs);
            }
            continue;
          }
          nextToken(el.name.c_str());
          int64_t n;
          if (!parseInt(b, e, n) || n < 0)
            src.failLine(Code::ParseError, sc.tokenLine(), "bad list length '" + std::string(b, e) + "'");
          const size_t listLine = sc.tokenLine();
          if (uint64_t(n) * 2 > uint64_t(sc.remaining()) + 1)
            src.failLine(Code::ParseError, listLine, "list length " + std::to_string(n) + " exceeds the data");
          const bool face = isFace && pr.role == kFace;
          if (face) {
            if (n < 3) src.failLine(Code::ParseError, listLine, "face with " + std::to_string(n) + " < 3 vertices");
            sink.begin();
          }
          for (int64_t j = 0; j < n; ++j) {
            nextToken(el.name.c_str());
            if (isFace && pr.role == kTexcoord) {
              double v;
              if (!parseDouble(b, e, v))
                src.failLine(Code::ParseError, sc.tokenLine(), "bad number '" + std::string(b, e) + "'");
              sink.polyUv.push_back(v);
            }
            if (!face) continue;
            int64_t idx;
            if (!parseInt(b, e, idx))
              src.failLine(Code::ParseError, sc.tokenLine(), "bad vertex index '" + std::string(b, e) + "'");
            if (!sink.add(idx))
              src.failLine(Code::IndexOutOfRange, sc.tokenLine(),
                           "vertex index " + std::to_string(idx) + " not in [0, " + std::to_string(nv) + ")");
          }
        }
        if (isFace && texcoords) sink.endFace();
      }
    }
  }
  if (texcoords && sink.uvsComplete && sink.cornerUv.size() == 2 * mesh.triangles.size())
    mesh.attributes.push_back(MeshAttribute{"uv", 2, true, std::move(sink.cornerUv)});
  else if (texcoords)
    result.warnings.push_back("texcoord dropped: a face's list does not hold 2 values per corner");
  // an attribute with a NaN or infinite value is dropped (positions and uvs fail above)
  auto& attrs = mesh.attributes;
  for (size_t k = 0; k < attrs.size();) {
    if (std::all_of(attrs[k].values.begin(), attrs[k].values.end(), [](double v) { return std::isfinite(v); })) {
      ++k;
      continue;
    }
    result.warnings.push_back("vertex property '" + attrs[k].name + "' dropped: a value is not finite");
    attrs.erase(attrs.begin() + ptrdiff_t(k));
  }
}

}  // namespace conformesh::io_detail
