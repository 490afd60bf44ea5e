// conformesh — Wavefront OBJ reader: v, vt, f (a, a/b, a/b/c, a//c; negative = relative indices);
// polygons fan-triangulated; other statements (vn, o, g, s, usemtl, mtllib, l, p, ...) ignored.
#include <cmath>
#include <string>
#include <vector>

#include "mesh/io_detail.h"

namespace conformesh::io_detail {

namespace {

bool tokenIs(const char* b, const char* e, const char* word) {
  size_t n = std::strlen(word);
  return size_t(e - b) == n && std::memcmp(b, word, n) == 0;
}

// Resolve an OBJ index (1-based, or negative relative to `count` elements defined so far) to a
// 0-based index. Positive indices are checked later (files may refer forward); -1 = invalid.
int64_t resolve(int64_t idx, size_t count) {
  if (idx > 0) return idx - 1;
  if (idx < 0 && int64_t(count) + idx >= 0) return int64_t(count) + idx;
  return -1;
}

}  // namespace

void readObj(const Source& src, const ReadOptions& opt, ReadResult& result) {
  result.format = MeshFormat::Obj;
  MeshBuffers& mesh = result.mesh;
  std::vector<double> uvList;          // vt u v, 2 per entry
  std::vector<int64_t> cornerUv;       // per triangle corner: vt index or -1
  bool anyCornerUv = false;
  bool trackUvs = opt.readUvs;
  std::vector<int64_t> polyV, polyT;  // current face's corners
  int64_t maxV = -1, maxT = -1;        // largest positive index used, checked at the end
  size_t maxVLine = 0, maxTLine = 0;

  const char* p = reinterpret_cast<const char*>(src.data);
  const char* const end = p + src.size;
  {
    // Pre-count "v" and "f" lines to reserve (growth copies cost more than this pass), and see
    // whether any "vt" exists (else corner uvs are not tracked).
    size_t nv = 0, nf = 0, nvt = 0;
    for (const char* q = p; q < end;) {
      while (q < end && (*q == ' ' || *q == '\t')) ++q;
      if (end - q > 1 && (q[1] == ' ' || q[1] == '\t')) {
        nv += q[0] == 'v';
        nf += q[0] == 'f';
      } else if (end - q > 2 && q[0] == 'v' && q[1] == 't') {
        ++nvt;
      }
      const void* nl = std::memchr(q, '\n', size_t(end - q));
      q = nl ? static_cast<const char*>(nl) + 1 : end;
    }
    mesh.positions.reserve(3 * nv);
    mesh.triangles.reserve(3 * nf);
    if (nvt == 0) trackUvs = false;
    else cornerUv.reserve(3 * nf);
  }
  size_t line = 0;
  const char *b, *e;
  while (p < end) {
    ++line;
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    const char* le = nl ? nl : end;
    TextScanner sc(p, le, '#', line);
    p = nl ? nl + 1 : end;
    if (!sc.next(b, e)) continue;

    if (tokenIs(b, e, "v")) {
      double xyz[3];
      for (double& c : xyz) {
        if (!sc.next(b, e)) src.failLine(Code::ParseError, line, "vertex needs 3 coordinates");
        if (!parseDouble(b, e, c))
          src.failLine(Code::ParseError, line, "bad coordinate '" + std::string(b, e) + "'");
        if (!std::isfinite(c)) src.failLine(Code::NonFiniteCoordinate, line, "non-finite coordinate");
      }
      if (mesh.positions.size() / 3 >= kMaxVertices) src.failLine(Code::TooLarge, line, "too many vertices");
      mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
    } else if (tokenIs(b, e, "vt")) {  // kept even when !readUvs: relative vt indices count them
      double uv[2] = {0.0, 0.0};
      for (int k = 0; k < 2; ++k) {
        if (!sc.next(b, e)) {
          if (k == 0) src.failLine(Code::ParseError, line, "texture coordinate needs a value");
          break;
        }
        if (!parseDouble(b, e, uv[k]))
          src.failLine(Code::ParseError, line, "bad texture coordinate '" + std::string(b, e) + "'");
        if (!std::isfinite(uv[k])) src.failLine(Code::NonFiniteCoordinate, line, "non-finite texture coordinate");
      }
      uvList.insert(uvList.end(), uv, uv + 2);
    } else if (tokenIs(b, e, "f") || tokenIs(b, e, "fo")) {
      polyV.clear();
      polyT.clear();
      const size_t nv = mesh.positions.size() / 3, nt = uvList.size() / 2;
      while (sc.next(b, e)) {
        const char* s1 = static_cast<const char*>(std::memchr(b, '/', size_t(e - b)));
        const char* ve = s1 ? s1 : e;
        int64_t idx;
        if (!parseInt(b, ve, idx)) src.failLine(Code::ParseError, line, "bad face corner '" + std::string(b, e) + "'");
        int64_t v = resolve(idx, nv);
        if (v < 0) src.failLine(Code::IndexOutOfRange, line, "vertex index " + std::to_string(idx) + " does not exist");
        if (v > maxV) {
          maxV = v;
          maxVLine = line;
        }
        polyV.push_back(v);
        int64_t t = -1;
        if (s1) {
          const char* tb = s1 + 1;
          const char* s2 = static_cast<const char*>(std::memchr(tb, '/', size_t(e - tb)));
          const char* te = s2 ? s2 : e;
          if (te > tb) {
            if (!parseInt(tb, te, idx))
              src.failLine(Code::ParseError, line, "bad face corner '" + std::string(b, e) + "'");
            t = resolve(idx, nt);
            if (t < 0)
              src.failLine(Code::IndexOutOfRange, line, "texture index " + std::to_string(idx) + " does not exist");
            if (t > maxT) {
              maxT = t;
              maxTLine = line;
            }
          }
          // The normal index (after the second '/') is not used.
        }
        polyT.push_back(t);
      }
      if (polyV.size() < 3)
        src.failLine(Code::ParseError, line, "face with " + std::to_string(polyV.size()) + " < 3 vertices");
      for (size_t i = 1; i + 1 < polyV.size(); ++i) {
        const size_t c[3] = {0, i, i + 1};
        for (size_t k : c) {
          mesh.triangles.push_back(uint32_t(polyV[k]));
          if (trackUvs) {
            cornerUv.push_back(polyT[k]);
            anyCornerUv |= polyT[k] >= 0;
          }
        }
      }
    }
    // Anything else (vn, vp, o, g, s, usemtl, mtllib, l, p, curv, ...) is not geometry we keep.
  }

  const size_t nv = mesh.positions.size() / 3;
  if (maxV >= int64_t(nv))
    src.failLine(Code::IndexOutOfRange, maxVLine,
                 "vertex index " + std::to_string(maxV + 1) + " > vertex count " + std::to_string(nv));
  if (maxT >= int64_t(uvList.size() / 2))
    src.failLine(Code::IndexOutOfRange, maxTLine,
                 "texture index " + std::to_string(maxT + 1) + " > vt count " + std::to_string(uvList.size() / 2));

  // Per-vertex uvs when each used vertex has exactly one vt.
  if (trackUvs && anyCornerUv) {
    std::vector<int64_t> vt(nv, -1);
    bool ok = true;
    for (size_t c = 0; c < cornerUv.size() && ok; ++c) {
      const uint32_t v = mesh.triangles[c];
      const int64_t t = cornerUv[c];
      if (t < 0) {
        ok = false;
      } else if (vt[v] < 0) {
        vt[v] = t;
      } else if (vt[v] != t && (uvList[2 * vt[v]] != uvList[2 * t] || uvList[2 * vt[v] + 1] != uvList[2 * t + 1])) {
        ok = false;
      }
    }
    if (ok) {
      mesh.uvs.assign(2 * nv, 0.0);
      for (size_t v = 0; v < nv; ++v)
        if (vt[v] >= 0) {
          mesh.uvs[2 * v] = uvList[2 * vt[v]];
          mesh.uvs[2 * v + 1] = uvList[2 * vt[v] + 1];
        }
    } else {
      result.warnings.push_back(
          "uvs dropped: some vertex has no vt or several different vt (a uv seam); positions are shared");
    }
  }
}

}  // namespace conformesh::io_detail

namespace conformesh::io_detail {

bool looksLikeObj(const uint8_t* data, size_t size) {
  const size_t n = size < 4096 ? size : 4096;
  if (std::memchr(data, '\0', n)) return false;
  const char* p = reinterpret_cast<const char*>(data);
  const char* const end = p + n;
  static const char* const kKeywords[] = {"v", "vt", "vn", "vp", "f", "fo", "o", "g", "s", "usemtl", "mtllib", "l", "p"};
  while (p < end) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    const char* le = nl ? nl : end;
    TextScanner sc(p, le, '#');
    const char *b, *e;
    if (sc.next(b, e)) {
      for (const char* k : kKeywords)
        if (tokenIs(b, e, k)) return true;
      return false;
    }
    p = nl ? nl + 1 : end;
  }
  return false;
}

}  // namespace conformesh::io_detail
