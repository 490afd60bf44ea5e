#include "core/detmath.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

// Constants: the hexadecimal literals were computed with mpmath at 300 bits (the split parts
// are the leading bits of the constant, so their products with small integers are exact).
// Series coefficients are written as the exact fractions 1/n! or 1/(2n+1): each literal
// quotient is rounded once, identically by every IEEE compiler.
namespace conformesh::dmath {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ln 2 = kLn2Hi + kLn2Lo; kLn2Hi has 42 significant bits (k·kLn2Hi exact for |k| < 2^11).
constexpr double kLn2Hi = 0x1.62e42fefa3800p-1;
constexpr double kLn2Lo = 0x1.ef35793c76730p-45;
constexpr double kInvLn2 = 0x1.71547652b82fep+0;
// π/2 = kPio2A + kPio2B + kPio2C; A and B have 33 significant bits (k·A, k·B exact for |k| < 2^20).
constexpr double kPio2A = 0x1.921fb54400000p+0;
constexpr double kPio2B = 0x1.0b4611a600000p-34;
constexpr double kPio2C = 0x1.3198a2e037073p-69;
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
// π/2 and π as a rounded double plus the rounding error.
constexpr double kPio2Hi = 0x1.921fb54442d18p+0;
constexpr double kPio2Lo = 0x1.1a62633145c07p-54;
constexpr double kPiHi = 0x1.921fb54442d18p+1;
constexpr double kPiLo = 0x1.1a62633145c07p-53;
constexpr double kSqrt2 = 0x1.6a09e667f3bcdp+0;
// atan(i/8) = kAtanHi[i] + kAtanLo[i], i = 0..8.
constexpr double kAtanHi[9] = {0.0,
                               0x1.fd5ba9aac2f6ep-4,
                               0x1.f5b75f92c80ddp-3,
                               0x1.6f61941e4def1p-2,
                               0x1.dac670561bb4fp-2,
                               0x1.1e00babdefeb4p-1,
                               0x1.4978fa3269ee1p-1,
                               0x1.700a7c5784634p-1,
                               0x1.921fb54442d18p-1};
constexpr double kAtanLo[9] = {0.0,
                               -0x1.cd37686760c17p-59,
                               0x1.8ab6e3cf7afbdp-57,
                               -0x1.c63aae6f6e918p-56,
                               0x1.a2b7f222f65e2p-56,
                               -0x1.928df287a668fp-58,
                               0x1.2419a87f2a458p-56,
                               -0x1.8c34d25aadef6p-56,
                               0x1.1a62633145c07p-55};

inline std::uint64_t bitsOf(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline double fromBits(std::uint64_t u) {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
//! 2^k for -1022 <= k <= 1023 (a normal double, built from its bits).
inline double pow2(int k) { return fromBits(std::uint64_t(k + 1023) << 52); }
inline bool isNaN(double x) { return x != x; }
inline bool isInf(double x) { return x == kInf || x == -kInf; }

// e^r − 1 − r for |r| <= ln2/2 + ε: Taylor terms r²/2! .. r^13/13! (the first omitted term,
// r^14/14!, is below 5e-18).
inline double expm1Tail(double r) {
  const double q = 1.0 / 2 + r * (1.0 / 6 + r * (1.0 / 24 + r * (1.0 / 120 + r * (1.0 / 720 + r * (1.0 / 5040 + r * (1.0 / 40320 + r * (1.0 / 362880 + r * (1.0 / 3628800 + r * (1.0 / 39916800 + r * (1.0 / 479001600 + r * (1.0 / 6227020800.0)))))))))));
  return r * r * q;
}

// sin and cos of |r| <= π/4 + ε (z = r²): Taylor to r^19 and r^20 (first omitted terms below
// 1e-19). cos uses 1 − z/2 rounded, plus the rounding error of that subtraction.
inline double sinKernel(double r) {
  const double z = r * r;
  const double s = -1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040 + z * (1.0 / 362880 + z * (-1.0 / 39916800 + z * (1.0 / 6227020800.0 + z * (-1.0 / 1307674368000.0 + z * (1.0 / 355687428096000.0 + z * (-1.0 / 121645100408832000.0))))))));
  return r + (r * z) * s;
}
inline double cosKernel(double r) {
  const double z = r * r;
  const double c = 1.0 / 24 + z * (-1.0 / 720 + z * (1.0 / 40320 + z * (-1.0 / 3628800 + z * (1.0 / 479001600 + z * (-1.0 / 87178291200.0 + z * (1.0 / 20922789888000.0 + z * (-1.0 / 6402373705728000.0 + z * (1.0 / 2432902008176640000.0))))))));
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + (z * z) * c);
}

//! x >= 0 finite reduced to r = x − k·π/2, |r| <= π/4 (+ rounding); returns k mod 4.
//! Three-part Cody–Waite: accurate while k < 2^20 (x < 1.6e6); larger x keep determinism but
//! lose accuracy (no Payne–Hanek reduction: the pipeline's angles are within a few multiples of π).
inline int reduceHalfPi(double x, double& r) {
  if (x <= 0x1.921fb54442d18p-1) {  // π/4
    r = x;
    return 0;
  }
  const double k = std::floor(x * kTwoOverPi + 0.5);
  r = ((x - k * kPio2A) - k * kPio2B) - k * kPio2C;
  return int(std::fmod(k, 4.0));  // exact
}

//! atan(a) for 0 <= a <= 1: atan(a) = atan(c) + atan(t), c = i/8 the nearest eighth,
//! t = (a − c)/(1 + a·c), |t| <= 1/16; atan(t) by Taylor to t^15 (omitted t^17/17 < 2^-68·t).
inline double atanUnit(double a) {
  const int i = int(a * 8.0 + 0.5);
  const double c = i * 0.125;
  const double t = (a - c) / (1.0 + a * c);
  const double z = t * t;
  const double p = -1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9 + z * (-1.0 / 11 + z * (1.0 / 13 + z * (-1.0 / 15))))));
  return kAtanHi[i] + (kAtanLo[i] + (t + (t * z) * p));
}

}  // namespace

// exp: x = k·ln2 + r (Cody–Waite, |r| <= ln2/2), e^x = 2^k·(1 + r + expm1Tail(r)).
double exp(double x) {
  if (isNaN(x)) return x;
  if (x > 709.782712893384) return kInf;  // ln(DBL_MAX) = 709.78271289338399...
  if (x < -745.1332191019412) return 0.0;  // ln(2^-1075): rounds to 0
  if (std::fabs(x) < 0x1p-54) return 1.0 + x;
  const double k = std::floor(x * kInvLn2 + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  const double e = 1.0 + (r + expm1Tail(r));
  const int ki = int(k);
  if (ki > 1023) return (e * 2.0) * pow2(ki - 1);
  if (ki < -1021) return (e * pow2(ki + 600)) * pow2(-600);  // subnormal result: one rounding here
  return e * pow2(ki);
}

// log: x = 2^e·m, m in (√½, √2], f = m − 1 (exact), s = f/(2 + f), so ln m = 2 atanh s
// = 2s + s·R(s²), R = Σ_{n>=1} 2 s^{2n}/(2n+1) (n <= 10; s² < 0.0295, omitted term < 1e-18 relative),
// and 2s = f − s·f gives ln m = f − s·(f − R) with the leading f exact.
double log(double x) {
  if (isNaN(x)) return x;
  if (x < 0) return kNaN;
  if (x == 0) return -kInf;
  if (x == kInf) return x;
  int e = 0;
  std::uint64_t u = bitsOf(x);
  if ((u >> 52) == 0) {  // subnormal
    x *= 0x1p54;
    e = -54;
    u = bitsOf(x);
  }
  e += int(u >> 52) - 1023;
  double m = fromBits((u & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1023) << 52));
  if (m > kSqrt2) {
    m *= 0.5;
    ++e;
  }
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double R = z * (2.0 / 3 + z * (2.0 / 5 + z * (2.0 / 7 + z * (2.0 / 9 + z * (2.0 / 11 + z * (2.0 / 13 + z * (2.0 / 15 + z * (2.0 / 17 + z * (2.0 / 19 + z * (2.0 / 21))))))))));
  const double lnm = f - s * (f - R);
  return e * kLn2Hi + (lnm + e * kLn2Lo);
}

// log1p: with u = 1 + x rounded, log1p(x) = ln(u)·x/(u − 1) cancels the rounding of u
// (Goldberg, "What every computer scientist should know about floating-point arithmetic",
// ACM Computing Surveys 23(1), 1991, Theorem 4, after Kahan).
double log1p(double x) {
  if (isNaN(x)) return x;
  if (x < -1.0) return kNaN;
  if (x == -1.0) return -kInf;
  if (x > 0x1p53) return log(x);  // 1 + x rounds to x; also keeps +inf
  const double u = 1.0 + x;
  if (u == 1.0) return x;
  return log(u) * (x / (u - 1.0));
}

double sin(double x) {
  if (isNaN(x) || isInf(x)) return isNaN(x) ? x : kNaN;
  const double a = std::fabs(x);
  double r;
  const int q = reduceHalfPi(a, r);
  double v;
  switch (q) {
    case 0: v = sinKernel(r); break;
    case 1: v = cosKernel(r); break;
    case 2: v = -sinKernel(r); break;
    default: v = -cosKernel(r); break;
  }
  return std::signbit(x) ? -v : v;  // odd by construction
}

double cos(double x) {
  if (isNaN(x) || isInf(x)) return isNaN(x) ? x : kNaN;
  double r;
  const int q = reduceHalfPi(std::fabs(x), r);
  switch (q) {
    case 0: return cosKernel(r);
    case 1: return -sinKernel(r);
    case 2: return -cosKernel(r);
    default: return sinKernel(r);
  }
}

double tan(double x) {
  if (isNaN(x) || isInf(x)) return isNaN(x) ? x : kNaN;
  double r;
  const int q = reduceHalfPi(std::fabs(x), r);
  const double s = sinKernel(r), c = cosKernel(r);
  const double v = (q & 1) ? -c / s : s / c;
  return std::signbit(x) ? -v : v;
}

// atan: |x| > 1 by atan|x| = π/2 − atan(1/|x|), then atanUnit.
double atan(double x) {
  if (isNaN(x)) return x;
  const double a = std::fabs(x);
  const double v = a <= 1.0 ? atanUnit(a) : kPio2Hi - (atanUnit(1.0 / a) - kPio2Lo);
  return std::signbit(x) ? -v : v;
}

// atan2: the angle of |y|/|x| or |x|/|y| (whichever is <= 1) by atanUnit, then the quadrant.
double atan2(double y, double x) {
  if (isNaN(x) || isNaN(y)) return x + y;
  const bool neg = std::signbit(y);
  const double ay = std::fabs(y), ax = std::fabs(x);
  double v;
  if (ay == 0) {
    v = std::signbit(x) ? kPiHi : 0.0;
  } else if (isInf(ay) || isInf(ax)) {
    if (isInf(ay) && isInf(ax)) v = x > 0 ? 0x1.921fb54442d18p-1 : 0x1.2d97c7f3321d2p+1;  // π/4, 3π/4
    else if (isInf(ay)) v = kPio2Hi;
    else v = x > 0 ? 0.0 : kPiHi;
  } else if (ax == 0) {
    v = kPio2Hi;
  } else {
    // angle of (ax, ay) in [0, π/2]
    double a = ay <= ax ? atanUnit(ay / ax) : kPio2Hi - (atanUnit(ax / ay) - kPio2Lo);
    v = x > 0 ? a : kPiHi - (a - kPiLo);
  }
  return neg ? -v : v;
}

// asin x = atan2(x, √(1 − x²)), acos x = atan2(√(1 − x²), x), with 1 − x² as (1 − |x|)(1 + |x|).
double asin(double x) {
  if (isNaN(x)) return x;
  const double a = std::fabs(x);
  if (a > 1.0) return kNaN;
  if (a < 0x1p-27) return x;  // x³/6 below half an ulp
  const double v = atan2(a, std::sqrt((1.0 - a) * (1.0 + a)));
  return std::signbit(x) ? -v : v;
}

double acos(double x) {
  if (isNaN(x)) return x;
  const double a = std::fabs(x);
  if (a > 1.0) return kNaN;
  return atan2(std::sqrt((1.0 - a) * (1.0 + a)), x);
}

// hypot: the inputs scaled by a power of two when the squares could overflow or underflow.
double hypot(double x, double y) { return hypot(x, y, 0.0); }

double hypot(double x, double y, double z) {
  if (isInf(x) || isInf(y) || isInf(z)) return kInf;
  if (isNaN(x) || isNaN(y) || isNaN(z)) return kNaN;
  double a = std::fabs(x), b = std::fabs(y), c = std::fabs(z);
  const double m = std::fmax(a, std::fmax(b, c));
  if (m == 0) return 0.0;
  double s = 1.0;
  if (m > 0x1p500) {
    a *= 0x1p-600, b *= 0x1p-600, c *= 0x1p-600;
    s = 0x1p600;
  } else if (m < 0x1p-500) {
    a *= 0x1p600, b *= 0x1p600, c *= 0x1p600;
    s = 0x1p-600;
  }
  return std::sqrt(a * a + b * b + c * c) * s;
}

}  // namespace conformesh::dmath
