// Exact planar predicates; see predicates.h. Shewchuk 1997, our implementation.
#include "planar/predicates.h"

#include <cmath>

#if defined(__clang__)
#pragma clang fp contract(off)
#endif

namespace conformesh::planar {
namespace {

// Machine epsilon as Shewchuk defines it: 2^-53 for IEEE double (half an ulp of 1).
constexpr double kEps = 1.1102230246251565e-16;
constexpr double kSplitter = 134217729.0;  // 2^27 + 1
constexpr double kCcwBoundA = (3.0 + 16.0 * kEps) * kEps;
constexpr double kIccBoundA = (10.0 + 96.0 * kEps) * kEps;

// x + y = a + b exactly (x = fl(a + b)).
inline void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  double bv = x - a;
  double av = x - bv;
  y = (a - av) + (b - bv);
}
inline void twoDiff(double a, double b, double& x, double& y) {
  x = a - b;
  double bv = a - x;
  double av = x + bv;
  y = (a - av) + (bv - b);
}
inline void split(double a, double& hi, double& lo) {
  double c = kSplitter * a;
  double big = c - a;
  hi = c - big;
  lo = a - hi;
}
// x + y = a * b exactly (Dekker's product, no FMA needed).
inline void twoProduct(double a, double b, double& x, double& y) {
  x = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  double e1 = x - ah * bh;
  double e2 = e1 - al * bh;
  double e3 = e2 - ah * bl;
  y = al * bl - e3;
}

// h = e + f (nonoverlapping expansions, increasing magnitude), zero components removed.
// Returns the length of h. h must not alias e or f.
int expSum(int elen, const double* e, int flen, const double* f, double* h) {
  double q, qn, hh;
  int ei = 0, fi = 0, hi = 0;
  double enow = elen ? e[0] : 0.0, fnow = flen ? f[0] : 0.0;
  if (elen == 0) {
    for (int i = 0; i < flen; ++i) h[i] = f[i];
    return flen;
  }
  if (flen == 0) {
    for (int i = 0; i < elen; ++i) h[i] = e[i];
    return elen;
  }
  if ((fnow > enow) == (fnow > -enow)) {
    q = enow;
    enow = (++ei < elen) ? e[ei] : 0.0;
  } else {
    q = fnow;
    fnow = (++fi < flen) ? f[fi] : 0.0;
  }
  while (ei < elen && fi < flen) {
    if ((fnow > enow) == (fnow > -enow)) {
      twoSum(q, enow, qn, hh);
      enow = (++ei < elen) ? e[ei] : 0.0;
    } else {
      twoSum(q, fnow, qn, hh);
      fnow = (++fi < flen) ? f[fi] : 0.0;
    }
    q = qn;
    if (hh != 0.0) h[hi++] = hh;
  }
  while (ei < elen) {
    twoSum(q, enow, qn, hh);
    enow = (++ei < elen) ? e[ei] : 0.0;
    q = qn;
    if (hh != 0.0) h[hi++] = hh;
  }
  while (fi < flen) {
    twoSum(q, fnow, qn, hh);
    fnow = (++fi < flen) ? f[fi] : 0.0;
    q = qn;
    if (hh != 0.0) h[hi++] = hh;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// h = b * e, zero components removed. h must hold 2 * elen doubles.
int expScale(int elen, const double* e, double b, double* h) {
  double q, sum, hh, p1, p0;
  int hi = 0;
  twoProduct(e[0], b, q, hh);
  if (hh != 0.0) h[hi++] = hh;
  for (int i = 1; i < elen; ++i) {
    twoProduct(e[i], b, p1, p0);
    twoSum(q, p0, sum, hh);
    if (hh != 0.0) h[hi++] = hh;
    twoSum(p1, sum, q, hh);
    if (hh != 0.0) h[hi++] = hh;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

// h = e * f. h needs 2 * elen * flen doubles, tmp needs as many plus 2 * elen.
int expMul(int elen, const double* e, int flen, const double* f, double* h, double* tmp) {
  double* part = tmp;                 // 2 * elen
  double* acc = tmp + 2 * elen;       // 2 * elen * flen
  int hlen = 0;
  double* cur = h;
  double* other = acc;
  for (int j = 0; j < flen; ++j) {
    int plen = expScale(elen, e, f[j], part);
    int n = expSum(hlen, cur, plen, part, other);
    double* t = cur;
    cur = other;
    other = t;
    hlen = n;
  }
  if (cur != h)
    for (int i = 0; i < hlen; ++i) h[i] = cur[i];
  return hlen;
}

inline double expEstimate(int n, const double* e) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += e[i];
  return s;
}

double orientExact(const double* a, const double* b, const double* c) {
  // (ax-cx)(by-cy) - (ay-cy)(bx-cx) with exact differences as 2-term expansions.
  double acx[2], acy[2], bcx[2], bcy[2];
  twoDiff(a[0], c[0], acx[1], acx[0]);
  twoDiff(a[1], c[1], acy[1], acy[0]);
  twoDiff(b[0], c[0], bcx[1], bcx[0]);
  twoDiff(b[1], c[1], bcy[1], bcy[0]);
  double t1[8], t2[8], tmp[16], r[16];
  int n1 = expMul(2, acx, 2, bcy, t1, tmp);
  int n2 = expMul(2, acy, 2, bcx, t2, tmp);
  for (int i = 0; i < n2; ++i) t2[i] = -t2[i];
  int n = expSum(n1, t1, n2, t2, r);
  return r[n - 1];
}

// Lifted term: (dx^2 + dy^2) * (ux * vy - uy * vx), all operands expansions.
int liftTerm(int dxn, const double* dx, int dyn, const double* dy, int uxn, const double* ux, int uyn,
             const double* uy, int vxn, const double* vx, int vyn, const double* vy, double* out) {
  double sq1[8], sq2[8], lift[16], m1[8], m2[8], minor[16], tmp[1024];
  int a = expMul(dxn, dx, dxn, dx, sq1, tmp);
  int b = expMul(dyn, dy, dyn, dy, sq2, tmp);
  int l = expSum(a, sq1, b, sq2, lift);
  int c = expMul(uxn, ux, vyn, vy, m1, tmp);
  int d = expMul(uyn, uy, vxn, vx, m2, tmp);
  for (int i = 0; i < d; ++i) m2[i] = -m2[i];
  int m = expSum(c, m1, d, m2, minor);
  return expMul(l, lift, m, minor, out, tmp);
}

double incircleExact(const double* a, const double* b, const double* c, const double* d) {
  double adx[2], ady[2], bdx[2], bdy[2], cdx[2], cdy[2];
  twoDiff(a[0], d[0], adx[1], adx[0]);
  twoDiff(a[1], d[1], ady[1], ady[0]);
  twoDiff(b[0], d[0], bdx[1], bdx[0]);
  twoDiff(b[1], d[1], bdy[1], bdy[0]);
  twoDiff(c[0], d[0], cdx[1], cdx[0]);
  twoDiff(c[1], d[1], cdy[1], cdy[0]);
  // Drop zero tails so exact differences (the common case) give short expansions.
  auto len = [](double* e) {
    if (e[0] == 0.0) {
      e[0] = e[1];
      return 1;
    }
    return 2;
  };
  int adxn = len(adx), adyn = len(ady), bdxn = len(bdx), bdyn = len(bdy), cdxn = len(cdx), cdyn = len(cdy);
  double ta[512], tb[512], tc[512], ab[1024], r[1536];
  int na = liftTerm(adxn, adx, adyn, ady, bdxn, bdx, bdyn, bdy, cdxn, cdx, cdyn, cdy, ta);
  int nb = liftTerm(bdxn, bdx, bdyn, bdy, cdxn, cdx, cdyn, cdy, adxn, adx, adyn, ady, tb);
  int nc = liftTerm(cdxn, cdx, cdyn, cdy, adxn, adx, adyn, ady, bdxn, bdx, bdyn, bdy, tc);
  int nab = expSum(na, ta, nb, tb, ab);
  int n = expSum(nab, ab, nc, tc, r);
  (void)expEstimate;
  return r[n - 1];
}

}  // namespace

PredicateStats& predicateStats() {
  thread_local PredicateStats s;
  return s;
}

double orient2d(const double* a, const double* b, const double* c) {
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double detsum;
  if (detleft > 0.0) {
    if (detright <= 0.0) return det;
    detsum = detleft + detright;
  } else if (detleft < 0.0) {
    if (detright >= 0.0) return det;
    detsum = -detleft - detright;
  } else {
    return det;
  }
  double bound = kCcwBoundA * detsum;
  if (det >= bound || -det >= bound) return det;
  ++predicateStats().orientExact;
  return orientExact(a, b, c);
}

double incircle(const double* a, const double* b, const double* c, const double* d) {
  double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  double alift = adx * adx + ady * ady;
  double cdxady = cdx * ady, adxcdy = adx * cdy;
  double blift = bdx * bdx + bdy * bdy;
  double adxbdy = adx * bdy, bdxady = bdx * ady;
  double clift = cdx * cdx + cdy * cdy;
  double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                     (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                     (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  double bound = kIccBoundA * permanent;
  if (det > bound || -det > bound) return det;
  ++predicateStats().incircleExact;
  return incircleExact(a, b, c, d);
}

}  // namespace conformesh::planar
