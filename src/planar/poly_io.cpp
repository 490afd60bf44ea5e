// Reader and writer for Triangle's .poly format; see poly_io.h.
#include "planar/poly_io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/status.h"

namespace conformesh::planar {
namespace {

class LineReader {
 public:
  explicit LineReader(const std::vector<uint8_t>& b) : b_(b) {}

  // Next non-empty line (comments removed) split into tokens; false at end of input.
  bool next(std::vector<std::string>& tok) {
    tok.clear();
    while (pos_ < b_.size()) {
      ++line_;
      size_t end = pos_;
      while (end < b_.size() && b_[end] != '\n') ++end;
      std::string cur;
      for (size_t i = pos_; i < end; ++i) {
        char c = char(b_[i]);
        if (c == '#') break;
        if (c == ' ' || c == '\t' || c == '\r' || c == ',') {
          if (!cur.empty()) tok.push_back(std::move(cur)), cur.clear();
        } else {
          cur.push_back(c);
        }
      }
      if (!cur.empty()) tok.push_back(std::move(cur));
      pos_ = end + 1;
      if (!tok.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void error(const std::string& msg) const {
    fail(Code::ParseError, Stage::Read, ".poly line " + std::to_string(line_) + ": " + msg);
  }
  void need(std::vector<std::string>& tok, size_t n, const char* what) {
    if (!next(tok)) error(std::string("unexpected end of file, expected ") + what);
    if (tok.size() < n) error(std::string("expected ") + std::to_string(n) + " numbers for " + what);
  }
  double real(const std::string& s) const {
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size() || s.empty()) error("'" + s + "' is not a number");
    if (!std::isfinite(v)) fail(Code::NonFiniteCoordinate, Stage::Read, ".poly line " + std::to_string(line_) + ": non-finite value");
    return v;
  }
  long long integer(const std::string& s) const {
    char* end = nullptr;
    errno = 0;
    long long v = std::strtoll(s.c_str(), &end, 10);
    if (end != s.c_str() + s.size() || s.empty() || errno == ERANGE) error("'" + s + "' is not an integer");
    return v;
  }
  size_t line() const { return line_; }

 private:
  const std::vector<uint8_t>& b_;
  size_t pos_ = 0, line_ = 0;
};

}  // namespace

Pslg readPoly(const std::vector<uint8_t>& bytes) {
  LineReader r(bytes);
  std::vector<std::string> tok;
  Pslg out;
  r.need(tok, 1, "the vertex header");
  long long nv = r.integer(tok[0]);
  long long dim = tok.size() > 1 ? r.integer(tok[1]) : 2;
  long long nattr = tok.size() > 2 ? r.integer(tok[2]) : 0;
  long long nvm = tok.size() > 3 ? r.integer(tok[3]) : 0;
  if (nv == 0) r.error("vertices in a separate .node file are not supported");
  if (nv < 0 || nv > (1LL << 30)) r.error("bad vertex count");
  if (dim != 2) r.error("dimension must be 2");
  if (nattr < 0 || nvm < 0 || nvm > 1) r.error("bad attribute / marker count");
  long long base = 0;
  out.points.resize(size_t(2 * nv));
  for (long long i = 0; i < nv; ++i) {
    r.need(tok, size_t(3 + nattr + nvm), "a vertex");
    long long id = r.integer(tok[0]);
    if (i == 0) {
      if (id != 0 && id != 1) r.error("the first vertex must be numbered 0 or 1");
      base = id;
    }
    if (id != i + base) r.error("vertex numbered " + std::to_string(id) + ", expected " + std::to_string(i + base));
    out.points[size_t(2 * i)] = r.real(tok[1]);
    out.points[size_t(2 * i + 1)] = r.real(tok[2]);
  }
  r.need(tok, 1, "the segment header");
  long long ns = r.integer(tok[0]);
  long long nsm = tok.size() > 1 ? r.integer(tok[1]) : 0;
  if (ns < 0 || ns > (1LL << 30) || nsm < 0 || nsm > 1) r.error("bad segment header");
  out.segments.resize(size_t(2 * ns));
  if (nsm) out.segmentMarkers.resize(size_t(ns));
  for (long long i = 0; i < ns; ++i) {
    r.need(tok, size_t(3 + nsm), "a segment");
    for (int k = 0; k < 2; ++k) {
      long long v = r.integer(tok[size_t(1 + k)]) - base;
      if (v < 0 || v >= nv)
        fail(Code::IndexOutOfRange, Stage::Read,
             ".poly line " + std::to_string(r.line()) + ": segment endpoint " + tok[size_t(1 + k)] + " does not exist");
      out.segments[size_t(2 * i + k)] = uint32_t(v);
    }
    if (nsm) out.segmentMarkers[size_t(i)] = int32_t(r.integer(tok[3]));
  }
  if (!r.next(tok)) return out;  // the hole section may be missing
  long long nh = r.integer(tok[0]);
  if (nh < 0 || nh > (1LL << 30)) r.error("bad hole count");
  for (long long i = 0; i < nh; ++i) {
    r.need(tok, 3, "a hole");
    out.holes.push_back(r.real(tok[1]));
    out.holes.push_back(r.real(tok[2]));
  }
  return out;  // regional attributes, if any, are ignored
}

std::string writePoly(const Pslg& p) {
  std::string s;
  char buf[128];
  size_t nv = p.points.size() / 2, ns = p.segments.size() / 2, nh = p.holes.size() / 2;
  std::snprintf(buf, sizeof buf, "%zu 2 0 0\n", nv);
  s += buf;
  for (size_t i = 0; i < nv; ++i) {
    std::snprintf(buf, sizeof buf, "%zu %.17g %.17g\n", i + 1, p.points[2 * i], p.points[2 * i + 1]);
    s += buf;
  }
  bool m = !p.segmentMarkers.empty();
  std::snprintf(buf, sizeof buf, "%zu %d\n", ns, m ? 1 : 0);
  s += buf;
  for (size_t i = 0; i < ns; ++i) {
    if (m)
      std::snprintf(buf, sizeof buf, "%zu %u %u %d\n", i + 1, p.segments[2 * i] + 1, p.segments[2 * i + 1] + 1,
                    p.segmentMarkers[i]);
    else
      std::snprintf(buf, sizeof buf, "%zu %u %u\n", i + 1, p.segments[2 * i] + 1, p.segments[2 * i + 1] + 1);
    s += buf;
  }
  std::snprintf(buf, sizeof buf, "%zu\n", nh);
  s += buf;
  for (size_t i = 0; i < nh; ++i) {
    std::snprintf(buf, sizeof buf, "%zu %.17g %.17g\n", i + 1, p.holes[2 * i], p.holes[2 * i + 1]);
    s += buf;
  }
  return s;
}

}  // namespace conformesh::planar
