// conformesh — exact decimal number parsing and printing for the text mesh formats.
#include <cstdio>
#include <cstdlib>

#include "mesh/io_detail.h"

namespace conformesh::io_detail {

namespace {

constexpr double kPow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// strtod on a NUL-terminated copy (the input bytes are not NUL-terminated). Relies on the "C"
// numeric locale, which the library never changes.
bool parseSlow(const char* b, const char* e, double& out) {
  char buf[400];
  size_t n = size_t(e - b);
  if (n == 0 || n >= sizeof(buf)) return false;
  std::memcpy(buf, b, n);
  buf[n] = '\0';
  char* endp = nullptr;
  out = std::strtod(buf, &endp);
  return endp == buf + n;
}

}  // namespace

bool parseDouble(const char* b, const char* e, double& out) {
  const char* p = b;
  bool neg = false;
  if (p < e && (*p == '+' || *p == '-')) {
    neg = *p == '-';
    ++p;
  }
  uint64_t m = 0;
  int sig = 0;      // significant digits accumulated in m
  int exp10 = 0;    // value = m * 10^exp10
  int mantissaDigits = 0;
  bool fast = true;
  for (; p < e && isDigit(*p); ++p, ++mantissaDigits) {
    if (sig < 19) {
      m = m * 10 + uint64_t(*p - '0');
      if (m != 0) ++sig;
    } else {
      fast = false;
    }
  }
  if (p < e && *p == '.') {
    ++p;
    for (; p < e && isDigit(*p); ++p, ++mantissaDigits) {
      if (sig < 19) {
        m = m * 10 + uint64_t(*p - '0');
        if (m != 0) ++sig;
        --exp10;
      } else {
        fast = false;
      }
    }
  }
  if (mantissaDigits == 0) return parseSlow(b, e, out);  // "nan", "inf", hex, or garbage
  if (p < e && (*p == 'e' || *p == 'E')) {
    ++p;
    bool eneg = false;
    if (p < e && (*p == '+' || *p == '-')) {
      eneg = *p == '-';
      ++p;
    }
    if (p >= e || !isDigit(*p)) return false;
    int x = 0;
    for (; p < e && isDigit(*p); ++p) {
      if (x < 100000) x = x * 10 + (*p - '0');
    }
    exp10 += eneg ? -x : x;
  }
  if (p != e) return false;
  if (m == 0) {
    out = neg ? -0.0 : 0.0;
    return true;
  }
  if (fast && m <= (uint64_t(1) << 53) && exp10 >= -22 && exp10 <= 22) {
    // Both m and 10^|exp10| are exact doubles: one correctly rounded operation (Clinger 1990).
    double v = double(m);
    v = exp10 < 0 ? v / kPow10[-exp10] : v * kPow10[exp10];
    out = neg ? -v : v;
    return true;
  }
  return parseSlow(b, e, out);
}

bool parseInt(const char* b, const char* e, int64_t& out) {
  const char* p = b;
  bool neg = false;
  if (p < e && (*p == '+' || *p == '-')) {
    neg = *p == '-';
    ++p;
  }
  if (p >= e) return false;
  int64_t v = 0;
  for (; p < e; ++p) {
    if (!isDigit(*p)) return false;
    if (v > ((int64_t(1) << 62) - (*p - '0')) / 10) return false;
    v = v * 10 + (*p - '0');
  }
  out = neg ? -v : v;
  return true;
}

void appendDouble(std::string& out, double v) {
  char buf[40];
  for (int prec = 15; prec <= 17; ++prec) {
    int n = std::snprintf(buf, sizeof(buf), "%.*g", prec, v);
    if (n <= 0 || n >= int(sizeof(buf))) break;
    if (prec == 17 || std::strtod(buf, nullptr) == v) {
      out.append(buf, size_t(n));
      return;
    }
  }
  fail(Code::InternalError, Stage::Write, "could not format a coordinate");
}

}  // namespace conformesh::io_detail
