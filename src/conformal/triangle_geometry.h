// conformesh — triangle angles from edge lengths, stable for needles.
//
// Angles by W. Kahan's formula ("Miscalculating area and angles of a needle-like triangle",
// 2014): exact to a few ulps even when one angle is below 1e-8 rad or close to pi, where the
// cosine law loses all digits.
#pragma once

#include <algorithm>
#include "core/constants.h"
#include <cmath>

#include "core/detmath.h"

namespace conformesh::conformal {


//! Angle (radians) opposite the side of length `c`, between the sides `a` and `b` (any order).
//! Lengths must be positive. Returns pi when c >= a + b and 0 when c <= |a - b| (the limits of
//! the triangle inequality, as in the extension of Springborn–Schröder–Pinkall 2008); `valid` is
//! set false in those cases.
inline double kahanAngle(double c, double a, double b, bool& valid) {
  if (a < b) std::swap(a, b);  // a >= b
  double mu;
  if (b >= c)
    mu = c - (a - b);
  else
    mu = b - (a - c);
  const double num = ((a - b) + c) * mu;
  const double den = (a + (b + c)) * ((a - c) + b);
  if (!(mu > 0.0)) {  // c <= a - b: degenerate, zero angle
    valid = false;
    return 0.0;
  }
  if (!(den > 0.0)) {  // c >= a + b: degenerate, straight angle
    valid = false;
    return kPi;
  }
  return 2.0 * dmath::atan(std::sqrt(num / den));
}

//! Corner angles of a triangle given by squared-log lengths lam[k] = 2 log l_k (edge k).
//! angle[k] is the angle opposite edge k. Overflow-safe for any finite lam (lengths are
//! normalized by the longest). Returns false when the triangle inequality fails.
inline bool anglesFromLogLengths(const double lam[3], double angle[3]) {
  const double m = std::max(lam[0], std::max(lam[1], lam[2]));
  // the longest is 1 (what exp(0) gives) without its exp: the flow calls this per face per step
  const double l0 = lam[0] == m ? 1.0 : dmath::exp(0.5 * (lam[0] - m));
  const double l1 = lam[1] == m ? 1.0 : dmath::exp(0.5 * (lam[1] - m));
  const double l2 = lam[2] == m ? 1.0 : dmath::exp(0.5 * (lam[2] - m));
  bool valid = true;
  angle[0] = kahanAngle(l0, l1, l2, valid);
  angle[1] = kahanAngle(l1, l2, l0, valid);
  angle[2] = kahanAngle(l2, l0, l1, valid);
  if (!valid) {
    // Consistent degenerate extension: pi opposite the longest edge, 0 elsewhere.
    int k = (l0 >= l1 && l0 >= l2) ? 0 : (l1 >= l2 ? 1 : 2);
    angle[0] = angle[1] = angle[2] = 0.0;
    angle[k] = kPi;
  }
  return valid;
}

//! Cotangent of an angle in (0, pi); +-huge at the limits instead of inf.
inline double cotOfAngle(double theta) {
  const double s = dmath::sin(theta);
  if (s < 1e-300) return theta < 1.0 ? 1e300 : -1e300;
  return dmath::cos(theta) / s;
}

}  // namespace conformesh::conformal
