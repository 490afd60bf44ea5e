// conformesh — OFF reader (Geomview): header keyword [ST][C][N][4][n]OFF, optional dimension
// (nOFF), counts (possibly on the header line), '#' comments, vertices (extra per-vertex values
// such as normals, colours, texture coordinates skipped to the end of the line), polygons with
// any number of vertices (fan-triangulated; per-face colour values skipped to the end of the line).
#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/io_detail.h"

namespace conformesh::io_detail {

namespace {

struct OffHeader {
  bool valid = false;
  bool homogeneous = false;  // '4': a fourth coordinate w divides x, y, z
  bool dimension = false;    // 'n': the dimension follows the keyword
};

OffHeader parseKeyword(const char* b, const char* e) {
  OffHeader h;
  size_t n = size_t(e - b);
  if (n < 3 || std::memcmp(e - 3, "OFF", 3) != 0) return h;
  const char* p = b;
  const char* stop = e - 3;
  if (stop - p >= 2 && p[0] == 'S' && p[1] == 'T') p += 2;
  if (p < stop && *p == 'C') ++p;
  if (p < stop && *p == 'N') ++p;
  if (p < stop && *p == '4') {
    h.homogeneous = true;
    ++p;
  }
  if (p < stop && *p == 'n') {
    h.dimension = true;
    ++p;
  }
  h.valid = p == stop;
  return h;
}

}  // namespace

bool looksLikeOff(const uint8_t* data, size_t size) {
  const char* b = reinterpret_cast<const char*>(data);
  TextScanner sc(b, b + std::min<size_t>(size, 4096), '#');
  const char *tb, *te;
  if (!sc.next(tb, te)) return false;
  return parseKeyword(tb, te).valid;
}

void readOff(const Source& src, const ReadOptions&, ReadResult& result) {
  result.format = MeshFormat::Off;
  MeshBuffers& mesh = result.mesh;
  const char* text = reinterpret_cast<const char*>(src.data);
  TextScanner sc(text, text + src.size, '#');
  const char *b, *e;

  auto nextInt = [&](const char* what, int64_t& v) {
    if (!sc.next(b, e)) src.failLine(Code::ParseError, sc.line(), std::string("end of file: expected ") + what);
    if (!parseInt(b, e, v))
      src.failLine(Code::ParseError, sc.tokenLine(), std::string("expected ") + what + ", got '" + std::string(b, e) + "'");
  };

  if (!sc.next(b, e)) src.failPlain(Code::EmptyMesh, "empty OFF file");
  OffHeader h = parseKeyword(b, e);
  int64_t nv = 0, nf = 0, ne = 0;
  int coords = 3;
  if (h.valid) {
    if (h.dimension) {
      int64_t dim;
      nextInt("the dimension (nOFF)", dim);
      if (dim != 2 && dim != 3)
        src.failLine(Code::ParseError, sc.tokenLine(), "only 2- and 3-dimensional OFF is supported");
      coords = int(dim);
    }
    nextInt("the vertex count", nv);
  } else if (src.forced && parseInt(b, e, nv)) {
    // Header keyword omitted (allowed by the OFF description): the counts start right away.
  } else {
    src.failLine(Code::ParseError, sc.tokenLine(), "expected an OFF header keyword, got '" + std::string(b, e) + "'");
  }
  nextInt("the face count", nf);
  if (sc.nextOnLine(b, e) && !parseInt(b, e, ne))
    src.failLine(Code::ParseError, sc.tokenLine(), "expected the edge count, got '" + std::string(b, e) + "'");
  if (nv < 0 || nf < 0) src.failLine(Code::ParseError, sc.tokenLine(), "negative count");
  const int values = coords + (h.homogeneous ? 1 : 0);
  // Each vertex value and each face token takes at least 2 bytes ("0 "); face: "3 a b c ".
  const uint64_t room = uint64_t(sc.remaining()) + 1;
  if (uint64_t(nv) > kMaxVertices || uint64_t(nf) > room / 8 ||
      uint64_t(nv) * 2 * uint64_t(values) + uint64_t(nf) * 8 > room)
    src.failLine(Code::TooLarge, sc.tokenLine(),
                 "header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                     " faces, more than the " + std::to_string(sc.remaining()) + " remaining bytes can hold");
  sc.skipLine();

  mesh.positions.resize(size_t(nv) * 3);
  for (int64_t v = 0; v < nv; ++v) {
    double x[4] = {0.0, 0.0, 0.0, 1.0};
    for (int k = 0; k < values; ++k) {
      int slot = (h.homogeneous && k == values - 1) ? 3 : k;
      if (!sc.next(b, e))
        src.failLine(Code::ParseError, sc.line(),
                     "end of file in vertex " + std::to_string(v) + " of " + std::to_string(nv));
      if (!parseDouble(b, e, x[slot]))
        src.failLine(Code::ParseError, sc.tokenLine(), "bad coordinate '" + std::string(b, e) + "'");
      if (!std::isfinite(x[slot])) src.failLine(Code::NonFiniteCoordinate, sc.tokenLine(), "non-finite coordinate");
    }
    for (int k = 0; k < 3; ++k) {
      double c = h.homogeneous ? x[k] / x[3] : x[k];
      if (!std::isfinite(c))
        src.failLine(Code::NonFiniteCoordinate, sc.tokenLine(), "homogeneous coordinate w = 0");
      mesh.positions[3 * size_t(v) + k] = c;
    }
    sc.skipLine();
  }

  mesh.triangles.reserve(size_t(nf) * 3);
  for (int64_t f = 0; f < nf; ++f) {
    int64_t k;
    nextInt("a face's vertex count", k);
    const size_t line = sc.tokenLine();
    if (k < 3) src.failLine(Code::ParseError, line, "face with " + std::to_string(k) + " < 3 vertices");
    if (uint64_t(k) * 2 > uint64_t(sc.remaining()) + 1)
      src.failLine(Code::ParseError, line, "face claims " + std::to_string(k) + " vertices, more than the file holds");
    int64_t first = 0, prev = 0;
    for (int64_t i = 0; i < k; ++i) {
      int64_t idx;
      nextInt("a vertex index", idx);
      if (idx < 0 || idx >= nv)
        src.failLine(Code::IndexOutOfRange, sc.tokenLine(),
                     "vertex index " + std::to_string(idx) + " not in [0, " + std::to_string(nv) + ")");
      if (i == 0) {
        first = idx;
      } else if (i >= 2) {
        mesh.triangles.push_back(uint32_t(first));
        mesh.triangles.push_back(uint32_t(prev));
        mesh.triangles.push_back(uint32_t(idx));
      }
      prev = idx;
    }
    sc.skipLine();
  }
}

}  // namespace conformesh::io_detail
