// conformesh — STL readers. Binary: 80-byte header, uint32 triangle count n, n records of 50 bytes
// (normal, 3 vertices as little-endian float32, uint16 attribute); the file size must be
// 84 + 50·n. Ascii: solid / facet normal / outer loop / vertex x y z / endloop / endfacet /
// endsolid (keywords case-insensitive; several solids allowed; loops of more than 3 vertices are
// fan-triangulated). Normals are ignored. STL has no shared vertices: equal positions are welded
// exactly, vertices numbered by first appearance.
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "mesh/io_detail.h"

namespace conformesh::io_detail {

namespace {

bool keywordIs(const char* b, const char* e, const char* word) {
  size_t n = std::strlen(word);
  if (size_t(e - b) != n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(b[i])) != word[i]) return false;
  return true;
}

inline uint32_t loadLE32(const uint8_t* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

}  // namespace

void readStlBinary(const Source& src, const ReadOptions&, ReadResult& result) {
  result.format = MeshFormat::StlBinary;
  if (src.size < 84)
    src.failOffset(Code::ParseError, src.size,
                   "binary STL ends inside the 84-byte header (file has " + std::to_string(src.size) + " bytes)");
  const uint64_t n = loadLE32(src.data + 80);
  const uint64_t need = 84 + 50 * n;
  if (need > src.size) {
    const uint64_t whole = (uint64_t(src.size) - 84) / 50;
    src.failOffset(Code::ParseError, 84 + 50 * whole,
                   "binary STL truncated: header says " + std::to_string(n) + " triangles (" + std::to_string(need) +
                       " bytes), the file has " + std::to_string(src.size) + " bytes (" + std::to_string(whole) +
                       " whole triangles)");
  }
  if (need < src.size) {
    if (!src.forced)
      src.failOffset(Code::ParseError, need, "binary STL size does not match its triangle count");
    result.warnings.push_back(std::to_string(src.size - need) + " bytes after the last STL triangle ignored");
  }
  if (3 * n > kMaxVertices) src.failPlain(Code::TooLarge, "too many triangles");

  weldBinaryStlRecords(src.data + 84, size_t(n), result.mesh, [&](size_t t, int k) {
    src.failOffset(Code::NonFiniteCoordinate, 84 + 50 * uint64_t(t) + 12 + 4 * uint64_t(k), "non-finite coordinate");
  });
}

void readStlAscii(const Source& src, const ReadOptions&, ReadResult& result) {
  result.format = MeshFormat::StlAscii;
  // Control bytes mean binary data: most often a binary STL whose header begins with "solid" but
  // whose size does not match its triangle count (truncated).
  for (size_t i = 0; i < src.size; ++i) {
    const uint8_t c = src.data[i];
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') {
      std::string hint;
      if (src.size >= 84) {
        const uint64_t n = uint64_t(loadLE32(src.data + 80));
        hint = "; as a binary STL, its size " + std::to_string(src.size) + " != 84 + 50 * " + std::to_string(n) +
               " (truncated?)";
      }
      src.failOffset(Code::ParseError, i, "binary byte in an ascii STL" + hint);
    }
  }
  const char* text = reinterpret_cast<const char*>(src.data);
  TextScanner sc(text, text + src.size, '\0');
  std::vector<double> soup;
  std::vector<double> loop;
  bool inLoop = false, sawSolid = false, sawEnd = false;
  size_t loopLine = 0;
  const char *b, *e;
  while (sc.next(b, e)) {
    if (keywordIs(b, e, "vertex")) {
      if (!inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'vertex' outside 'outer loop'");
      for (int k = 0; k < 3; ++k) {
        double c;
        if (!sc.nextOnLine(b, e)) src.failLine(Code::ParseError, sc.line(), "vertex needs 3 coordinates");
        if (!parseDouble(b, e, c))
          src.failLine(Code::ParseError, sc.tokenLine(), "bad coordinate '" + std::string(b, e) + "'");
        if (!std::isfinite(c)) src.failLine(Code::NonFiniteCoordinate, sc.tokenLine(), "non-finite coordinate");
        loop.push_back(c);
      }
    } else if (keywordIs(b, e, "facet")) {
      if (inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'facet' inside a loop");
      sc.skipLine();  // "normal nx ny nz": not used
    } else if (keywordIs(b, e, "outer")) {
      if (!sc.nextOnLine(b, e) || !keywordIs(b, e, "loop"))
        src.failLine(Code::ParseError, sc.tokenLine(), "expected 'outer loop'");
      if (inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "nested 'outer loop'");
      inLoop = true;
      loopLine = sc.tokenLine();
      loop.clear();
    } else if (keywordIs(b, e, "endloop")) {
      if (!inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'endloop' without 'outer loop'");
      const size_t k = loop.size() / 3;
      if (k < 3) src.failLine(Code::ParseError, loopLine, "facet with " + std::to_string(k) + " < 3 vertices");
      for (size_t i = 1; i + 1 < k; ++i) {
        soup.insert(soup.end(), loop.begin(), loop.begin() + 3);
        soup.insert(soup.end(), loop.begin() + 3 * i, loop.begin() + 3 * (i + 2));
      }
      inLoop = false;
    } else if (keywordIs(b, e, "endfacet")) {
      if (inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'endfacet' before 'endloop'");
    } else if (keywordIs(b, e, "solid")) {
      if (inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'solid' inside a loop");
      sawSolid = true;
      sawEnd = false;
      sc.skipLine();  // the solid's name
    } else if (keywordIs(b, e, "endsolid")) {
      if (inLoop) src.failLine(Code::ParseError, sc.tokenLine(), "'endsolid' inside a loop");
      sawEnd = true;
      sc.skipLine();
    } else {
      std::string tok(b, std::min<size_t>(size_t(e - b), 40));
      src.failLine(Code::ParseError, sc.tokenLine(), "unexpected '" + tok + "' in ascii STL");
    }
  }
  if (inLoop) src.failLine(Code::ParseError, loopLine, "end of file inside 'outer loop'");
  if (!sawSolid) result.warnings.push_back("ascii STL without 'solid' line");
  else if (!sawEnd) result.warnings.push_back("ascii STL without 'endsolid' line (truncated?)");
  if (soup.size() / 3 > kMaxVertices) src.failPlain(Code::TooLarge, "too many triangles");
  weldSoupExact(soup, result.mesh);
}

}  // namespace conformesh::io_detail
