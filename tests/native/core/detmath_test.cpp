#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "core/detmath.h"

// conformesh::dmath against the platform libm (glibc natively, musl in WASM; both within about
// 1 ulp of the exact value): the largest ulp distance over 10^6 random arguments per function and
// range must stay within the documented bound; special values exact; symmetries exact.
namespace dm = conformesh::dmath;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kSamples = 1000000;

//! Distance in units in the last place: the count of doubles between a and b.
std::int64_t ulpDistance(double a, double b) {
  if (a == b) return 0;
  auto ordered = [](double x) {
    std::int64_t i;
    std::memcpy(&i, &x, sizeof i);
    return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
  };
  const std::int64_t d = ordered(a) - ordered(b);
  return d < 0 ? -d : d;
}

struct Sampler {
  std::mt19937_64 rng{20261128};
  //! Uniform in [lo, hi].
  double uniform(double lo, double hi) { return lo + (hi - lo) * (double(rng() >> 11) * 0x1p-53); }
  //! ±2^e·m with e uniform in [emin, emax) and a random mantissa.
  double magnitude(int emin, int emax, bool sign = true) {
    const double m = 1.0 + double(rng() >> 12) * 0x1p-52;
    const int e = emin + int(rng() % std::uint64_t(emax - emin));
    const double v = std::ldexp(m, e);
    return sign && (rng() & 1) ? -v : v;
  }
};

//! Largest ulp distance of f from ref over kSamples arguments drawn by gen.
std::int64_t maxUlp1(double (*f)(double), double (*ref)(double), const std::function<double()>& gen) {
  std::int64_t worst = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double x = gen();
    const std::int64_t d = ulpDistance(f(x), ref(x));
    if (d > worst) worst = d;
  }
  return worst;
}

double stdExp(double x) { return std::exp(x); }
double stdLog(double x) { return std::log(x); }
double stdLog1p(double x) { return std::log1p(x); }
double stdSin(double x) { return std::sin(x); }
double stdCos(double x) { return std::cos(x); }
double stdTan(double x) { return std::tan(x); }
double stdAtan(double x) { return std::atan(x); }
double stdAsin(double x) { return std::asin(x); }
double stdAcos(double x) { return std::acos(x); }

}  // namespace

TEST_CASE("dmath: max ulp error against std:: on 10^6 random arguments per function and range") {
  Sampler s;
  struct Case {
    const char* name;
    double (*f)(double);
    double (*ref)(double);
    std::function<double()> gen;
    std::int64_t bound;
  };
  const Case cases[] = {
      {"exp [-745, 709.7]", dm::exp, stdExp, [&] { return s.uniform(-745, 709.7); }, 2},
      {"exp [-1, 1]", dm::exp, stdExp, [&] { return s.uniform(-1, 1); }, 2},
      {"log (0, DBL_MAX], all exponents", dm::log, stdLog, [&] { return s.magnitude(-1074, 1024, false); }, 2},
      {"log [0.5, 2]", dm::log, stdLog, [&] { return s.uniform(0.5, 2); }, 2},
      {"log1p [-1, 1]", dm::log1p, stdLog1p, [&] { return s.uniform(-1, 1); }, 3},
      {"log1p ±2^[-60, 60]", dm::log1p, stdLog1p, [&] { return s.magnitude(-60, 60, false); }, 3},
      {"sin [-10, 10]", dm::sin, stdSin, [&] { return s.uniform(-10, 10); }, 3},
      {"sin [-1e5, 1e5]", dm::sin, stdSin, [&] { return s.uniform(-1e5, 1e5); }, 3},
      {"cos [-10, 10]", dm::cos, stdCos, [&] { return s.uniform(-10, 10); }, 3},
      {"cos [-1e5, 1e5]", dm::cos, stdCos, [&] { return s.uniform(-1e5, 1e5); }, 3},
      {"tan [-10, 10]", dm::tan, stdTan, [&] { return s.uniform(-10, 10); }, 4},
      {"atan [-4, 4]", dm::atan, stdAtan, [&] { return s.uniform(-4, 4); }, 3},
      {"atan ±2^[-40, 40]", dm::atan, stdAtan, [&] { return s.magnitude(-40, 40); }, 3},
      {"asin [-1, 1]", dm::asin, stdAsin, [&] { return s.uniform(-1, 1); }, 4},
      {"acos [-1, 1]", dm::acos, stdAcos, [&] { return s.uniform(-1, 1); }, 4},
  };
  for (const Case& c : cases) {
    const std::int64_t worst = maxUlp1(c.f, c.ref, c.gen);
    MESSAGE(std::string(c.name) << ": max " << worst << " ulp (bound " << c.bound << ")");
    CHECK_MESSAGE(worst <= c.bound, std::string(c.name));
  }

  std::int64_t atan2Worst = 0, atan2WideWorst = 0, hypotWorst = 0, hypotWideWorst = 0, hypot3Worst = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double y = s.uniform(-1, 1), x = s.uniform(-1, 1);
    atan2Worst = std::max(atan2Worst, ulpDistance(dm::atan2(y, x), std::atan2(y, x)));
    hypotWorst = std::max(hypotWorst, ulpDistance(dm::hypot(x, y), std::hypot(x, y)));
    const double z = s.uniform(-1, 1);
    hypot3Worst = std::max(hypot3Worst, ulpDistance(dm::hypot(x, y, z), std::sqrt(double((long double)x * x + (long double)y * y + (long double)z * z))));
    const double yw = s.magnitude(-300, 300), xw = s.magnitude(-300, 300);
    atan2WideWorst = std::max(atan2WideWorst, ulpDistance(dm::atan2(yw, xw), std::atan2(yw, xw)));
    const double hw1 = s.magnitude(-1074, 1023), hw2 = hw1 * s.uniform(0.5, 2.0);
    hypotWideWorst = std::max(hypotWideWorst, ulpDistance(dm::hypot(hw1, hw2), std::hypot(hw1, hw2)));
  }
  MESSAGE("atan2 [-1, 1]^2: max " << atan2Worst << " ulp; atan2 ±2^[-300, 300]: " << atan2WideWorst
          << "; hypot [-1, 1]^2: " << hypotWorst << "; hypot all exponents: " << hypotWideWorst
          << "; hypot3 [-1, 1]^3 (vs long double): " << hypot3Worst);
  CHECK(atan2Worst <= 3);
  CHECK(atan2WideWorst <= 3);
  CHECK(hypotWorst <= 2);
  CHECK(hypotWideWorst <= 2);
  CHECK(hypot3Worst <= 2);
}

TEST_CASE("dmath: special values") {
  const double pi = 3.141592653589793, pio2 = 1.5707963267948966, pio4 = 0.7853981633974483;
  CHECK(dm::exp(0.0) == 1.0);
  CHECK(dm::exp(-0.0) == 1.0);
  CHECK(dm::exp(kInf) == kInf);
  CHECK(dm::exp(-kInf) == 0.0);
  CHECK(dm::exp(710.0) == kInf);
  CHECK(dm::exp(-746.0) == 0.0);
  CHECK(dm::exp(-740.0) > 0.0);  // subnormal
  CHECK(std::isnan(dm::exp(kNaN)));
  CHECK(ulpDistance(dm::exp(1.0), 2.718281828459045) <= 1);

  CHECK(dm::log(1.0) == 0.0);
  CHECK(dm::log(0.0) == -kInf);
  CHECK(dm::log(-0.0) == -kInf);
  CHECK(dm::log(kInf) == kInf);
  CHECK(std::isnan(dm::log(-1.0)));
  CHECK(std::isnan(dm::log(kNaN)));
  CHECK(ulpDistance(dm::log(2.0), 0.6931471805599453) <= 1);
  CHECK(ulpDistance(dm::log(4.9e-324), -744.4400719213812) <= 1);

  CHECK(dm::log1p(0.0) == 0.0);
  CHECK(std::signbit(dm::log1p(-0.0)));
  CHECK(dm::log1p(-1.0) == -kInf);
  CHECK(dm::log1p(kInf) == kInf);
  CHECK(std::isnan(dm::log1p(-2.0)));
  CHECK(dm::log1p(1e-300) == 1e-300);

  CHECK(dm::sin(0.0) == 0.0);
  CHECK(std::signbit(dm::sin(-0.0)));
  CHECK(dm::cos(0.0) == 1.0);
  CHECK(dm::tan(0.0) == 0.0);
  CHECK(std::signbit(dm::tan(-0.0)));
  for (double v : {kInf, -kInf, kNaN}) {
    CHECK(std::isnan(dm::sin(v)));
    CHECK(std::isnan(dm::cos(v)));
    CHECK(std::isnan(dm::tan(v)));
  }
  CHECK(ulpDistance(dm::sin(pio2), 1.0) == 0);
  CHECK(ulpDistance(dm::cos(pi), -1.0) == 0);

  CHECK(dm::atan(0.0) == 0.0);
  CHECK(std::signbit(dm::atan(-0.0)));
  CHECK(dm::atan(1.0) == pio4);
  CHECK(dm::atan(kInf) == pio2);
  CHECK(dm::atan(-kInf) == -pio2);
  CHECK(std::isnan(dm::atan(kNaN)));

  // atan2: C99 Annex F.9.1.4
  CHECK(dm::atan2(0.0, 1.0) == 0.0);
  CHECK(std::signbit(dm::atan2(-0.0, 1.0)));
  CHECK(dm::atan2(0.0, -0.0) == pi);
  CHECK(dm::atan2(-0.0, -1.0) == -pi);
  CHECK(dm::atan2(0.0, 0.0) == 0.0);
  CHECK(dm::atan2(1.0, 0.0) == pio2);
  CHECK(dm::atan2(-1.0, -0.0) == -pio2);
  CHECK(dm::atan2(kInf, kInf) == pio4);
  CHECK(dm::atan2(kInf, -kInf) == 2.356194490192345);
  CHECK(dm::atan2(-kInf, 3.0) == -pio2);
  CHECK(dm::atan2(1.0, kInf) == 0.0);
  CHECK(dm::atan2(-1.0, -kInf) == -pi);
  CHECK(dm::atan2(1.0, -1.0) == 2.356194490192345);
  CHECK(dm::atan2(1.0, 1.0) == pio4);
  CHECK(dm::atan2(1e-300, -1e300) == pi);
  CHECK(std::isnan(dm::atan2(kNaN, 1.0)));
  CHECK(std::isnan(dm::atan2(1.0, kNaN)));

  CHECK(dm::asin(1.0) == pio2);
  CHECK(dm::asin(-1.0) == -pio2);
  CHECK(dm::asin(0.0) == 0.0);
  CHECK(std::signbit(dm::asin(-0.0)));
  CHECK(std::isnan(dm::asin(1.5)));
  CHECK(dm::acos(1.0) == 0.0);
  CHECK(dm::acos(-1.0) == pi);
  CHECK(dm::acos(0.0) == pio2);
  CHECK(std::isnan(dm::acos(-1.0000001)));
  CHECK(ulpDistance(dm::asin(0.5), 0.5235987755982989) <= 1);
  CHECK(ulpDistance(dm::acos(0.5), 1.0471975511965979) <= 1);

  CHECK(dm::hypot(3.0, 4.0) == 5.0);
  CHECK(dm::hypot(-3.0, 4.0, 12.0) == 13.0);
  CHECK(dm::hypot(0.0, -0.0) == 0.0);
  CHECK(dm::hypot(kInf, kNaN) == kInf);
  CHECK(dm::hypot(kNaN, -kInf, 1.0) == kInf);
  CHECK(std::isnan(dm::hypot(kNaN, 1.0)));
  CHECK(ulpDistance(dm::hypot(1e300, 1e300), 1.4142135623730951e300) <= 1);
  CHECK(ulpDistance(dm::hypot(3e-310, 4e-310), 5e-310) <= 1);
  CHECK(dm::hypot(1e308, 1e308) < kInf);
}

TEST_CASE("dmath: symmetries hold exactly") {
  Sampler s;
  int failures = 0;
  for (int i = 0; i < 100000; ++i) {
    const double x = i % 2 ? s.uniform(0, 20) : s.magnitude(-30, 30, false);
    const double u = s.uniform(0, 1), y = s.uniform(-5, 5);
    failures += dm::sin(-x) != -dm::sin(x);
    failures += dm::cos(-x) != dm::cos(x);
    failures += dm::tan(-x) != -dm::tan(x);
    failures += dm::atan(-x) != -dm::atan(x);
    failures += dm::asin(-u) != -dm::asin(u);
    failures += dm::atan2(-x, y) != -dm::atan2(x, y);
    failures += dm::hypot(-x, y) != dm::hypot(x, -y);
    failures += dm::hypot(x, y, u) != dm::hypot(-x, -y, -u);
  }
  CHECK(failures == 0);
}
