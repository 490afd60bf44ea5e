// conformesh — exact decimal number parsing and printing for the text mesh formats.
#include <charconv>
#include <cmath>
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

namespace {

// Round the 17 significant digits `in` (first digit at 10^x) to `prec` digits, half up.
void roundDigits(const char* in, int prec, char* out, int& x) {
  std::memcpy(out, in, size_t(prec));
  if (in[prec] < '5') return;
  for (int i = prec - 1; i >= 0; --i) {
    if (out[i] != '9') {
      ++out[i];
      return;
    }
    out[i] = '0';
  }
  out[0] = '1';  // 9.99..9 rounded up to 10.0..0
  ++x;
}

// Append sign, digits d[0..k) (trailing zeros dropped) with d[0] at 10^x: fixed notation for
// -5 <= x <= 15, else scientific ("1.25e-07" style, as printf's %g would choose).
template <class Out>
void appendDigits(Out& out, bool neg, const char* d, int k, int x) {
  while (k > 1 && d[k - 1] == '0') --k;
  if (neg) out += '-';
  if (x >= -5 && x <= 15) {
    if (x < 0) {
      out += "0.";
      out.append(size_t(-x - 1), '0');
      out.append(d, size_t(k));
    } else if (x + 1 >= k) {
      out.append(d, size_t(k));
      out.append(size_t(x + 1 - k), '0');
    } else {
      out.append(d, size_t(x + 1));
      out += '.';
      out.append(d + x + 1, size_t(k - x - 1));
    }
    return;
  }
  out += d[0];
  if (k > 1) {
    out += '.';
    out.append(d + 1, size_t(k - 1));
  }
  out += x < 0 ? "e-" : "e+";
  const int ax = x < 0 ? -x : x;
  if (ax >= 100) out += char('0' + ax / 100);
  out += char('0' + (ax / 10) % 10);
  out += char('0' + ax % 10);
}

// A fixed-capacity character sink (a formatted double never needs more than 32 characters).
struct CharBuf {
  char data[40];
  size_t n = 0;
  void append(const char* s, size_t k) {
    std::memcpy(data + n, s, k);
    n += k;
  }
  void append(size_t k, char c) {
    std::memset(data + n, c, k);
    n += k;
  }
  CharBuf& operator+=(char c) {
    data[n++] = c;
    return *this;
  }
  CharBuf& operator+=(const char* s) {
    append(s, std::strlen(s));
    return *this;
  }
  void clear() { n = 0; }
};

}  // namespace

size_t formatDouble(double v, char* out) {
  if (!std::isfinite(v)) fail(Code::NonFiniteCoordinate, Stage::Write, "cannot write a non-finite value");
  if (v == 0.0) {
    const char* z = std::signbit(v) ? "-0" : "0";
    std::memcpy(out, z, std::strlen(z));
    return std::strlen(z);
  }
  // 17 significant digits always read back to v; then try 15 and 16 (the shortest that reads back
  // wins; the check parses the candidate, so a double rounding can only cost a digit, never
  // exactness).
  char buf[48];
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  // the same characters as printf's "%.16e" (both are exact; to_chars is specified as printf),
  // without printf's multi-precision path, where most of the time writing a mesh went
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf) - 1, v, std::chars_format::scientific, 16);
  const int n = r.ec == std::errc() ? int(r.ptr - buf) : -1;
  if (n > 0) buf[n] = '\0';
#else
  const int n = std::snprintf(buf, sizeof(buf), "%.16e", v);  // [-]d.dddddddddddddddde[+-]XX
#endif
  const bool neg = buf[0] == '-';
  const char* p = buf + (neg ? 1 : 0);
  if (n <= 0 || n >= int(sizeof(buf)) || p[1] != '.' || p[18] != 'e')
    fail(Code::InternalError, Stage::Write, "could not format a coordinate");
  char digits[18];
  digits[0] = p[0];
  std::memcpy(digits + 1, p + 2, 16);
  digits[17] = '0';
  const int exp10 = std::atoi(p + 19);
  CharBuf c;
  for (int prec = 15; prec <= 16; ++prec) {
    char d[17];
    int x = exp10;
    roundDigits(digits, prec, d, x);
    c.clear();
    appendDigits(c, neg, d, prec, x);
    double back;
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
    // from_chars is correctly rounded, as parseDouble is (the same value, so the same choice),
    // and about five times cheaper: the check was a fifth of writing a mesh
    const std::from_chars_result fr = std::from_chars(c.data, c.data + c.n, back);
    const bool read = fr.ec == std::errc() && fr.ptr == c.data + c.n;
#else
    const bool read = parseDouble(c.data, c.data + c.n, back);
#endif
    if (read && back == v) {
      std::memcpy(out, c.data, c.n);
      return c.n;
    }
  }
  c.clear();
  appendDigits(c, neg, digits, 17, exp10);
  std::memcpy(out, c.data, c.n);
  return c.n;
}

void appendDouble(std::string& out, double v) {
  char buf[kMaxDoubleChars];
  out.append(buf, formatDouble(v, buf));
}

}  // namespace conformesh::io_detail
