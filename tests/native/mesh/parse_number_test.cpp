// Number text: parseDouble agrees with strtod bit for bit; appendDouble reads back exactly.
#include <doctest/doctest.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>

#include "mesh/io_detail.h"
#include "mesh_io_test_util.h"

using namespace conformesh;
using namespace conformesh::io_detail;
using namespace conformesh::test;

namespace {

double strtodOf(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

double randomDouble(Rng& r) {
  switch (r.below(6)) {
    case 0: return r.coordinate();
    case 1: return std::ldexp(r.uniform(), int(r.below(2098)) - 1074);  // any exponent, subnormals
    case 2: return double(int64_t(r.next() >> r.below(64)));           // integers
    case 3: return std::round(r.coordinate() * 1e6) / 1e6;              // short decimals
    case 4: {
      double v;
      uint64_t bits = r.next() & 0x7FEFFFFFFFFFFFFFull;  // any finite bit pattern
      std::memcpy(&v, &bits, 8);
      return v;
    }
    default: return -double(float(r.coordinate()));  // float values
  }
}

}  // namespace

TEST_CASE("appendDouble: exact round trip (checked with strtod), at most 17 digits") {
  Rng r(7);
  for (int i = 0; i < 20000; ++i) {
    const double v = randomDouble(r);
    std::string s;
    appendDouble(s, v);
    CAPTURE(s);
    CHECK(sameBits(strtodOf(s), v));
    size_t digits = 0;
    for (char c : s) {
      if (c == 'e') break;
      digits += c >= '0' && c <= '9';
    }
    CHECK(digits <= 17 + 5);  // fixed notation may add up to 5 leading zeros
  }
  for (double v : {0.1, 1.0, -2.5, 1e16, 1e-5, 123456.789, 5e-324, 1.7976931348623157e308, -0.0}) {
    std::string s;
    appendDouble(s, v);
    CAPTURE(s);
    CHECK(sameBits(strtodOf(s), v));
  }
  std::string s;
  appendDouble(s, 0.1);
  CHECK(s == "0.1");
}

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
TEST_CASE("formatDouble's digits: to_chars scientific 16 writes what printf's %.16e writes") {
  // formatDouble takes its 17 digits from to_chars where the library has it (printf elsewhere,
  // e.g. the WASM build): the files must not depend on which
  Rng r(11);
  for (int i = 0; i < 200000; ++i) {
    const double v = i < 100000 ? randomDouble(r) : -randomDouble(r);
    char a[64], b[64];
    std::snprintf(a, sizeof(a), "%.16e", v);
    const std::to_chars_result t = std::to_chars(b, b + sizeof(b) - 1, v, std::chars_format::scientific, 16);
    REQUIRE(t.ec == std::errc());
    *t.ptr = '\0';
    CAPTURE(a);
    CHECK(std::string(a) == std::string(b));
  }
}
#endif

TEST_CASE("parseDouble agrees with strtod bit for bit") {
  Rng r(8);
  for (int i = 0; i < 20000; ++i) {
    // Random decimal strings: sign, up to 25 digits with a point somewhere, optional exponent.
    std::string t;
    if (r.below(2)) t += r.below(2) ? "-" : "+";
    const int nd = 1 + int(r.below(25));
    const int point = int(r.below(uint32_t(nd + 1)));
    for (int k = 0; k < nd; ++k) {
      if (k == point) t += '.';
      t += char('0' + r.below(10));
    }
    if (r.below(2)) t += (r.below(2) ? "e" : "E") + std::to_string(int(r.below(700)) - 350);
    double v;
    CAPTURE(t);
    REQUIRE(parseDouble(t.data(), t.data() + t.size(), v));
    CHECK(sameBits(v, strtodOf(t)));
  }
  for (const char* bad : {"", "-", ".", "1e", "1e+", "1.2.3", "0x", "abc", "1,5", "--1"}) {
    double v;
    CAPTURE(bad);
    CHECK_FALSE(parseDouble(bad, bad + std::strlen(bad), v));
  }
  double v;
  const std::string nan = "nan", inf = "-inf";
  CHECK((parseDouble(nan.data(), nan.data() + 3, v) && std::isnan(v)));
  CHECK((parseDouble(inf.data(), inf.data() + 4, v) && std::isinf(v)));
}
