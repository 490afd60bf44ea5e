// conformesh — Wavefront OBJ reader: v, vt, vn, f (a, a/b, a/b/c, a//c; negative = relative
// indices); polygons fan-triangulated; other statements (o, g, s, usemtl, mtllib, l, p, ...) ignored.
#include <algorithm>
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

// Per-corner indices into a list of `k`-component values (vt or vn) as mesh data: per vertex
// when the corners of every vertex agree on the value (0 for vertices no face uses), else per
// corner. Empty values when some corner has no index.
struct CornerData {
  bool perCorner = false;
  std::vector<double> values;
};
CornerData cornerValues(const std::vector<double>& list, int k, const std::vector<int64_t>& cornerIndex,
                        const std::vector<uint32_t>& triangles, size_t nv) {
  CornerData out;
  std::vector<int64_t> first(nv, -1);
  for (size_t c = 0; c < cornerIndex.size(); ++c) {
    const int64_t i = cornerIndex[c];
    if (i < 0) return out;
    int64_t& f = first[triangles[c]];
    if (f < 0) f = i;
    else if (f != i && !out.perCorner)
      out.perCorner = !std::equal(&list[size_t(k * f)], &list[size_t(k * f)] + k, &list[size_t(k * i)]);
  }
  if (!out.perCorner) {
    out.values.assign(size_t(k) * nv, 0.0);
    for (size_t v = 0; v < nv; ++v)
      if (first[v] >= 0) std::copy_n(&list[size_t(k * first[v])], k, &out.values[size_t(k) * v]);
    return out;
  }
  out.values.resize(size_t(k) * cornerIndex.size());
  for (size_t c = 0; c < cornerIndex.size(); ++c)
    std::copy_n(&list[size_t(k * cornerIndex[c])], k, &out.values[size_t(k) * c]);
  return out;
}

}  // namespace

void readObj(const Source& src, const ReadOptions& opt, ReadResult& result) {
  result.format = MeshFormat::Obj;
  MeshBuffers& mesh = result.mesh;
  std::vector<double> uvList;          // vt u v, 2 per entry
  std::vector<int64_t> cornerUv;       // per triangle corner: vt index or -1
  bool anyCornerUv = false;
  bool trackUvs = opt.readUvs;
  std::vector<double> normalList;      // vn x y z, 3 per entry
  std::vector<int64_t> cornerNormal;   // per triangle corner: vn index or -1
  bool anyCornerNormal = false;
  bool trackNormals = opt.readAttributes;
  std::vector<int64_t> polyV, polyT, polyN;  // current face's corners
  int64_t maxV = -1, maxT = -1, maxN = -1;   // largest positive index used, checked at the end
  size_t maxVLine = 0, maxTLine = 0;

  const char* p = reinterpret_cast<const char*>(src.data);
  const char* const end = p + src.size;
  {
    // Pre-count "v" and "f" lines to reserve (growth copies cost more than this pass), and see
    // whether any "vt" / "vn" exists (else corner uvs / normals are not tracked).
    size_t nv = 0, nf = 0, nvt = 0, nvn = 0;
    for (const char* q = p; q < end;) {
      while (q < end && (*q == ' ' || *q == '\t')) ++q;
      if (end - q > 1 && (q[1] == ' ' || q[1] == '\t')) {
        nv += q[0] == 'v';
        nf += q[0] == 'f';
      } else if (end - q > 2 && q[0] == 'v' && q[1] == 't') {
        ++nvt;
      } else if (end - q > 2 && q[0] == 'v' && q[1] == 'n') {
        ++nvn;
      }
      const void* nl = std::memchr(q, '\n', size_t(end - q));
      q = nl ? static_cast<const char*>(nl) + 1 : end;
    }
    mesh.positions.reserve(3 * nv);
    mesh.triangles.reserve(3 * nf);
    if (nvt == 0) trackUvs = false;
    else cornerUv.reserve(3 * nf);
    if (nvn == 0) trackNormals = false;
    else if (trackNormals) cornerNormal.reserve(3 * nf);
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

    // three finite numbers of a v (or, `normal`, a vn) line
    auto read3 = [&](double* xyz, bool normal) {
      for (int k = 0; k < 3; ++k) {
        if (!sc.next(b, e)) src.failLine(Code::ParseError, line, normal ? "normal needs 3 coordinates" : "vertex needs 3 coordinates");
        if (!parseDouble(b, e, xyz[k]))
          src.failLine(Code::ParseError, line, (normal ? "bad normal coordinate '" : "bad coordinate '") + std::string(b, e) + "'");
        if (!std::isfinite(xyz[k]))
          src.failLine(Code::NonFiniteCoordinate, line, normal ? "non-finite normal coordinate" : "non-finite coordinate");
      }
    };
    if (tokenIs(b, e, "v")) {
      double xyz[3];
      read3(xyz, false);
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
    } else if (tokenIs(b, e, "vn")) {  // kept even when not tracked: relative vn indices count them
      double n[3];
      read3(n, true);
      normalList.insert(normalList.end(), n, n + 3);
    } else if (tokenIs(b, e, "f") || tokenIs(b, e, "fo")) {
      polyV.clear();
      polyT.clear();
      polyN.clear();
      const size_t nv = mesh.positions.size() / 3, nt = uvList.size() / 2, nn = normalList.size() / 3;
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
        int64_t t = -1, n = -1;
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
          // the normal index, when normals are read: a bad one leaves the corner without (the
          // normals are then dropped with a warning, as before they were read at all)
          if (trackNormals && s2 && s2 + 1 < e && parseInt(s2 + 1, e, idx)) {
            n = resolve(idx, nn);
            maxN = std::max(maxN, n);
          }
        }
        polyT.push_back(t);
        polyN.push_back(n);
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
          if (trackNormals) {
            cornerNormal.push_back(polyN[k]);
            anyCornerNormal |= polyN[k] >= 0;
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

  if (maxN >= int64_t(normalList.size() / 3))
    for (int64_t& n : cornerNormal) n = n < int64_t(normalList.size() / 3) ? n : -1;

  // uvs per vertex when each used vertex has one vt value, else per corner (uv seams); normals
  // the same way, as the attribute "normal".
  if (trackUvs && anyCornerUv) {
    CornerData d = cornerValues(uvList, 2, cornerUv, mesh.triangles, nv);
    if (d.values.empty()) result.warnings.push_back("uvs dropped: some face corners have no vt");
    else if (!d.perCorner) mesh.uvs = std::move(d.values);
    else mesh.attributes.push_back(MeshAttribute{"uv", 2, true, std::move(d.values)});
  }
  if (trackNormals && anyCornerNormal) {
    CornerData d = cornerValues(normalList, 3, cornerNormal, mesh.triangles, nv);
    if (d.values.empty()) result.warnings.push_back("normals dropped: some face corners have no vn");
    else mesh.attributes.push_back(MeshAttribute{"normal", 3, d.perCorner, std::move(d.values)});
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
