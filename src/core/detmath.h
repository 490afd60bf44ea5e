#pragma once
// Deterministic elementary functions: the same bits natively (glibc) and in WASM (musl).
//
// Every function here is built from + − × ÷ and sqrt only (which IEEE 754 rounds correctly, so
// identically on every target), exact bit operations (scaling by powers of two), floor, and
// fixed-order polynomial evaluation; the library is compiled with -ffp-contract=off, so no FMA
// changes the rounding either. The platform libm is never called. Accuracy: a few ulp (the
// measured maxima against std:: on 10^6 random arguments are asserted in
// tests/native/core/detmath_test.cpp). Special values (NaN, ±inf, ±0) follow C99 Annex F.
//
// Methods: Cody–Waite additive argument reduction with a constant split into exactly
// representable parts (W. J. Cody, W. Waite, "Software Manual for the Elementary Functions",
// Prentice-Hall 1980; J.-M. Muller, "Elementary Functions: Algorithms and Implementation",
// 3rd ed. 2016, ch. 11), then truncated Taylor series of the reduced argument with the
// truncation below 2^-56 relative. Each function's reduction is described in detmath.cpp.
namespace conformesh::dmath {

double exp(double x);
double log(double x);
//! log(1 + x), accurate for tiny x.
double log1p(double x);
double sin(double x);
double cos(double x);
double tan(double x);
double atan(double x);
//! Angle of (x, y) in [-π, π], quadrant and signed zeros as C99 atan2.
double atan2(double y, double x);
double asin(double x);
double acos(double x);
//! sqrt(x² + y²) without overflow or underflow of the squares.
double hypot(double x, double y);
double hypot(double x, double y, double z);

}  // namespace conformesh::dmath
