#include <doctest/doctest.h>

#include <cmath>

#include "planar/predicates.h"

using conformesh::planar::incircle;
using conformesh::planar::orient2d;

TEST_CASE("orient2d: points a few ulps off the line y = x get the exact sign") {
  // p = (0.5 + i·u, 0.5 + j·u), u = ulp(0.5): p is left of q -> r exactly when j > i.
  const double u = std::ldexp(1.0, -53);
  const double q[2] = {12, 12}, r[2] = {24, 24};
  int naiveWrong = 0, wrong = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      double p[2] = {0.5 + i * u, 0.5 + j * u};
      double o = orient2d(p, q, r);
      int expect = j > i ? 1 : (j < i ? -1 : 0);
      int got = o > 0 ? 1 : (o < 0 ? -1 : 0);
      if (got != expect) ++wrong;
      double naive = (p[0] - r[0]) * (q[1] - r[1]) - (p[1] - r[1]) * (q[0] - r[0]);
      int ns = naive > 0 ? 1 : (naive < 0 ? -1 : 0);
      if (ns != expect) ++naiveWrong;
    }
  }
  CHECK(wrong == 0);
  CHECK(naiveWrong > 0);  // the input really is near-degenerate for plain doubles
}

TEST_CASE("orient2d: 1 ulp off a long segment, both sides and on it") {
  const double a[2] = {-1e6, 3.0}, b[2] = {1e6, 3.0};
  double on[2] = {0.123456789, 3.0};
  double above[2] = {0.123456789, std::nextafter(3.0, 4.0)};
  double below[2] = {0.123456789, std::nextafter(3.0, 2.0)};
  CHECK(orient2d(a, b, on) == 0);
  CHECK(orient2d(a, b, above) > 0);
  CHECK(orient2d(a, b, below) < 0);
  CHECK(orient2d(b, a, above) < 0);
}

TEST_CASE("incircle: exactly cocircular points far from the origin, and 1 ulp off") {
  // The 12 lattice points of x^2 + y^2 = 25, scaled by 2^-20 and shifted by (1e6, -7e5):
  // all exactly representable, so every 4-tuple is exactly cocircular.
  const double s = std::ldexp(1.0, -20), x0 = 1e6, y0 = -7e5;
  const int pts[12][2] = {{5, 0}, {4, 3}, {3, 4}, {0, 5}, {-3, 4}, {-4, 3}, {-5, 0}, {-4, -3}, {-3, -4}, {0, -5}, {3, -4}, {4, -3}};
  double p[12][2];
  for (int i = 0; i < 12; ++i) {
    p[i][0] = x0 + pts[i][0] * s;
    p[i][1] = y0 + pts[i][1] * s;
  }
  int nonzero = 0;
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b)
      for (int c = b + 1; c < 12; ++c)
        for (int d = 0; d < 12; ++d)
          if (d != a && d != b && d != c && incircle(p[a], p[b], p[c], p[d]) != 0) ++nonzero;
  CHECK(nonzero == 0);
  // (5, 0) moved one ulp outward / inward along x; a, b, c counter-clockwise.
  double out[2] = {std::nextafter(p[0][0], 2e6), p[0][1]};
  double in[2] = {std::nextafter(p[0][0], 0.0), p[0][1]};
  CHECK(incircle(p[1], p[3], p[6], out) < 0);
  CHECK(incircle(p[1], p[3], p[6], in) > 0);
  CHECK(incircle(p[3], p[1], p[6], in) < 0);  // clockwise triple flips the sign
}

TEST_CASE("incircle: cocircular unit grid squares") {
  // Every unit square of a grid is cocircular; offset by a value that makes the differences
  // inexact (0.1 is not dyadic but the grid points are exact multiples of 2^-4 here).
  int bad = 0;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      double x = 1000.0 + i * 0.0625, y = 1000.0 + j * 0.0625, h = 0.0625;
      double a[2] = {x, y}, b[2] = {x + h, y}, c[2] = {x + h, y + h}, d[2] = {x, y + h};
      if (incircle(a, b, c, d) != 0) ++bad;
      double e[2] = {x + h / 2, y + h / 2};
      if (!(incircle(a, b, c, e) > 0)) ++bad;
    }
  CHECK(bad == 0);
}
