#include "remesh/optimize.h"
#include "core/constants.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "planar/predicates.h"
#include "quality/aabb_tree.h"
#include "core/detmath.h"
#include "core/triangle_corner.h"
#include "core/vertex_stars.h"

namespace conformesh::optimization {
namespace {

//! x² as one product (std::pow(x, 2) goes through libm in some builds).
inline double sq(double x) { return x * x; }

constexpr double kRadToDeg = 57.295779513082320876798;

using planar::orient2d;

// The smallest angle of a 3D triangle is at the corner opposite its shortest edge: the length
// of the cross product and the dot product of the two edges there (angle = atan2(cr, dt)).
struct Corner {
  double cr, dt;
};

// The cross product's length is twice the area whichever two sides it takes, and the dot
// product at the corner opposite the shortest side follows from the squared lengths (law of
// cosines: (lu + lx - ls) / 2, with no cancellation: that corner's angle is at most 60 degrees,
// its cosine at least 1/2). No branch on which side is the shortest: it follows no pattern a
// predictor could learn, and the cross product need not wait for it (the optimization ran 15 %
// faster than with the two sides at that corner picked first; the same angles up to rounding).
inline Corner smallestCorner(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, bc = c - b, ca = a - c;
  const double lab = dot(ab, ab), lbc = dot(bc, bc), lca = dot(ca, ca);
  const double shortest = std::min(lab, std::min(lbc, lca));
  return {norm(cross(ab, bc)), 0.5 * (lab + lbc + lca - 2 * shortest)};
}

double cornerDeg(const Corner& k) { return ((k.cr == 0 && k.dt == 0) ? 0.0 : dmath::atan2(k.cr, k.dt)) * kRadToDeg; }

// cornerDeg without atan2 (NaN for cr = dt = 0): atan(z) = z · P(z²) on [0, 1], the
// other octants by symmetry; P the polynomial of Abramowitz–Stegun 4.4.49 (Hastings 1955),
// |error| <= 2e-8 rad (1.2e-6 degrees; optimize.h promises 1e-4).
double cornerDegApprox(const Corner& k) {
  constexpr double kHalfPi = 1.57079632679489661923;
  const double c = k.cr, d = std::abs(k.dt);
  const bool steep = c > d;
  const double z = steep ? d / c : c / d, z2 = z * z;
  const double p = 1 + z2 * (-0.3333314528 + z2 * (0.1999355085 + z2 * (-0.1420889944 + z2 * (0.1065626393 + z2 * (-0.0752896400 + z2 * (0.0429096138 + z2 * (-0.0161657367 + z2 * 0.0028662257)))))));
  double r = steep ? kHalfPi - z * p : z * p;
  if (k.dt < 0) r = kPi - r;
  return r * kRadToDeg;
}

// The optimizer works with cornerDegApprox's values (a tenth of atan2's cost): the moves and
// flips are ranked and decided by them. Only where the bound is at stake, within kApproxErrDeg
// of it, does it take the exact angle (atan2), so that no triangle at or above the bound ever
// ends below it. The bound has a margin of 8 over the polynomial's error (the test measures it).
constexpr double kApproxErrDeg = 1e-5;

// The corners after and before corner c.
constexpr int kNext[3] = {1, 2, 0}, kPrev[3] = {2, 0, 1};

// Circumcenter of a planar triangle; false when it is degenerate.
bool circumcenter(const double* a, const double* b, const double* c, double out[2]) {
  const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  const double d = 2 * (bx * cy - by * cx);
  if (!(std::abs(d) > 0)) return false;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  out[0] = a[0] + (cy * b2 - by * c2) / d;
  out[1] = a[1] + (bx * c2 - cx * b2) / d;
  return std::isfinite(out[0]) && std::isfinite(out[1]);
}

struct Mesh {
  std::vector<double>& xy;
  std::vector<uint32_t>& tri;
  std::vector<Vec3>& pos;
  const std::vector<uint8_t>& fixed;
  std::vector<uint32_t> starStart, starTri;  // CSR vertex -> triangles
  std::vector<uint32_t> adj;                 // triangle adjacency (see buildAdjacency)
  std::vector<double> minAngle;              // cached 3D min angle per triangle (degrees, approximate: kApproxErrDeg)
  // the guard (SurfaceSamples): per triangle a list (head, next) of the points whose planar
  // position it contains, and the largest squared 3D distance from them to the triangle
  const SurfaceSamples* guard = nullptr;
  std::vector<uint32_t> head, next;
  std::vector<double> err;
  std::vector<uint32_t> pending;  // rebucket's scratch list (kept to spare an allocation per move)
  std::vector<double> fresh;      // tryMove's: the star's new min angles
  // the valence operations (OptimizeOptions::valenceOperations): per vertex its triangle count
  // and the count its planar angle sum asks for (6 inside the patch); empty when off
  std::vector<int> deg, ideal;
  const OptimizeOptions* options = nullptr;  // for keptEdge

  const double* p(uint32_t v) const { return &xy[2 * size_t(v)]; }
  double triMin(uint32_t t) const {
    const uint32_t* v = &tri[3 * size_t(t)];
    return minAngleDeg3Approx(pos[v[0]], pos[v[1]], pos[v[2]]);
  }
  double triMinExact(uint32_t t) const {
    const uint32_t* v = &tri[3 * size_t(t)];
    return minAngleDeg3(pos[v[0]], pos[v[1]], pos[v[2]]);
  }
  void cacheAll() {
    minAngle.resize(tri.size() / 3);
    for (size_t t = 0; t < minAngle.size(); ++t) minAngle[t] = triMin(uint32_t(t));
  }
  void buildStars() { vertexStars(tri, xy.size() / 2, starStart, starTri); }
};


// The guard (see SurfaceSamples in the header). Each guard point is listed in the triangle
// that contains it in the plane (a floating-point test: the guard is a bound on a distance, not
// part of the mesh's validity, and a point found in no triangle is simply not tracked); err[t] is
// the largest squared 3D distance from t's points to t. A change of a star keeps the output's
// distance from those points within max(tolerance, the largest err of the star) measured as the
// distance to the nearest triangle of the star.
inline double cross2(const double* a, const double* b, const double* p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}
bool contains(const Mesh& m, const uint32_t* t, const double* p) {
  return cross2(m.p(t[0]), m.p(t[1]), p) >= 0 && cross2(m.p(t[1]), m.p(t[2]), p) >= 0 && cross2(m.p(t[2]), m.p(t[0]), p) >= 0;
}

double distance2(const Mesh& m, const uint32_t* t, const Vec3& x) {
  return quality::distanceSquared(x, quality::closestPointOnTriangle(x, m.pos[t[0]], m.pos[t[1]], m.pos[t[2]]));
}

// Sort the guard points pts into the triangles tris (ascending indices) that contain them; the
// lists of tris must be empty. A point on an edge goes to the first of them (smallest index)
// containing it; points in none of them (beyond a boundary chord) are not tracked.
void bucketGuard(Mesh& m, const std::vector<uint32_t>& tris, const std::vector<uint32_t>& pts) {
  if (tris.empty() || pts.empty()) return;
  const double* xy = m.guard->xy.data();
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (const uint32_t k : pts)
    for (int d = 0; d < 2; ++d) lo[d] = std::min(lo[d], xy[2 * size_t(k) + d]), hi[d] = std::max(hi[d], xy[2 * size_t(k) + d]);
  // a grid over the points (far fewer than the triangles: a patch's input vertices against its
  // output mesh), about one point per cell; each triangle then tests the points of the cells its
  // box covers (a point in a triangle is in a cell of its box: the cells are monotone in x, y)
  const int g = std::max(1, std::min(4096, int(std::sqrt(double(pts.size())))));
  const double scale[2] = {hi[0] > lo[0] ? g / (hi[0] - lo[0]) : 0.0, hi[1] > lo[1] ? g / (hi[1] - lo[1]) : 0.0};
  auto cell = [&](double x, int d) {  // clamped before the conversion (corners far off the points' box; NaN -> 0)
    const double f = (x - lo[d]) * scale[d];
    return f > 0 ? (f < g - 1 ? int(f) : g - 1) : 0;
  };
  std::vector<uint32_t> start(size_t(g) * g + 1, 0), items;
  auto cellOf = [&](uint32_t k) {
    const double* p = &xy[2 * size_t(k)];
    if (!(p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1])) return size_t(SIZE_MAX);  // NaN
    return size_t(cell(p[1], 1)) * g + cell(p[0], 0);
  };
  for (const uint32_t k : pts)
    if (const size_t c = cellOf(k); c != SIZE_MAX) ++start[c + 1];
  for (size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  items.resize(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const uint32_t k : pts)
      if (const size_t c = cellOf(k); c != SIZE_MAX) items[fill[c]++] = k;
  }
  std::vector<uint8_t> placed(start.back(), 0);  // per item
  // the cells of the triangles' corners, once per vertex (cell is monotone: the cells of a
  // triangle's box are those between its corners' cells)
  std::vector<int> vcell(m.xy.size(), -1);
  auto vertexCell = [&](uint32_t v, int d) {
    int& c = vcell[2 * size_t(v) + d];
    if (c < 0) c = cell(m.xy[2 * size_t(v) + d], d);
    return c;
  };
  for (const uint32_t t : tris) {
    const uint32_t* v = &m.tri[3 * size_t(t)];
    int r[4];  // i0, j0, i1, j1
    for (int d = 0; d < 2; ++d) {
      const int c0 = vertexCell(v[0], d), c1 = vertexCell(v[1], d), c2 = vertexCell(v[2], d);
      r[d] = std::min({c0, c1, c2});
      r[2 + d] = std::max({c0, c1, c2});
    }
    for (int j = r[1]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[2]; ++i) {
        const size_t c = size_t(j) * g + i;
        for (uint32_t q = start[c]; q < start[c + 1]; ++q) {
          const uint32_t k = items[q];
          if (placed[q] || !contains(m, v, &xy[2 * size_t(k)])) continue;
          placed[q] = 1;
          m.next[k] = m.head[t];
          m.head[t] = k;
          m.err[t] = std::max(m.err[t], distance2(m, v, m.guard->pos[k]));
        }
      }
  }
}

// All the guard points into all triangles.
void bucketGuard(Mesh& m) {
  const size_t nt = m.tri.size() / 3, ns = m.guard->pos.size();
  m.head.assign(nt, kNoTriangle);
  m.next.assign(ns, kNoTriangle);
  m.err.assign(nt, 0.0);
  std::vector<uint32_t> tris(nt), pts(ns);
  for (size_t t = 0; t < nt; ++t) tris[t] = uint32_t(t);
  for (size_t k = 0; k < ns; ++k) pts[k] = uint32_t(k);
  bucketGuard(m, tris, pts);
}

// The buckets a previous call left (m.head, m.next, m.err) after vertices moved: only the
// triangles `changed` (ascending; every triangle with a moved vertex among them) can have lost
// or gained points. Their points and the untracked ones are sorted again into them.
void rebucketGuard(Mesh& m, const std::vector<uint32_t>& changed) {
  const size_t ns = m.guard->pos.size();
  std::vector<uint8_t> tracked(ns, 0);
  for (const uint32_t h : m.head)
    for (uint32_t k = h; k != kNoTriangle; k = m.next[k]) tracked[k] = 1;
  std::vector<uint32_t> pts;
  for (const uint32_t t : changed) {
    for (uint32_t k = m.head[t]; k != kNoTriangle; k = m.next[k]) tracked[k] = 0;
    m.head[t] = kNoTriangle;
    m.err[t] = 0;
  }
  for (size_t k = 0; k < ns; ++k)
    if (!tracked[k]) {
      m.next[k] = kNoTriangle;
      pts.push_back(uint32_t(k));
    }
  bucketGuard(m, changed, pts);
}

// Would the guard keep the change that turned the region of triangles from[0..nFrom) (whose
// lists hold the points) into to[0..nTo)? The same slots for a move or a flip; a collapse leaves
// two fewer. `moved`: how far the change moved the 3D surface at most (a bound on the change of
// every point's distance; infinity when unknown).
bool guardAccepts(const Mesh& m, const uint32_t* from, size_t nFrom, const uint32_t* to, size_t nTo, double moved = INFINITY) {
  if (!m.guard) return true;
  double before = 0;
  for (size_t i = 0; i < nFrom; ++i) before = std::max(before, m.err[from[i]]);
  const double allowed = std::max(before, sq(m.guard->tolerance));
  if (std::sqrt(before) + moved <= m.guard->tolerance) return true;  // no point can get past it
  for (size_t i = 0; i < nFrom; ++i)
    for (uint32_t k = m.head[from[i]]; k != kNoTriangle; k = m.next[k]) {
      double d = INFINITY;
      for (size_t j = 0; j < nTo && d > allowed; ++j) d = std::min(d, distance2(m, &m.tri[3 * size_t(to[j])], m.guard->pos[k]));
      if (d > allowed) return false;
    }
  return true;
}
// A star, or the two triangles of a flip: the same slots before and after.
bool guardAccepts(const Mesh& m, const uint32_t* ts, size_t n, double moved = INFINITY) { return guardAccepts(m, ts, n, ts, n, moved); }

// After a kept change: the guard points of ts[0..n) go to their new triangles.
void rebucket(Mesh& m, const uint32_t* ts, size_t n) {
  if (!m.guard) return;
  std::vector<uint32_t>& pts = m.pending;
  pts.clear();
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t k = m.head[ts[i]]; k != kNoTriangle; k = m.next[k]) pts.push_back(k);
    m.head[ts[i]] = kNoTriangle;
    m.err[ts[i]] = 0;
  }
  for (uint32_t k : pts)
    for (size_t j = 0; j < n; ++j) {
      const uint32_t t = ts[j];
      if (!contains(m, &m.tri[3 * size_t(t)], &m.guard->xy[2 * size_t(k)])) continue;
      m.next[k] = m.head[t];
      m.head[t] = k;
      m.err[t] = std::max(m.err[t], distance2(m, &m.tri[3 * size_t(t)], m.guard->pos[k]));
      break;
    }
}

// Triangle (a, b, c) strictly positive in the plane, relative to its size: neither inverted nor
// a sliver.
bool positiveInPlane(const double* a, const double* b, const double* c) {
  const double l2 = std::max({sq(b[0] - a[0]) + sq(b[1] - a[1]), sq(c[0] - b[0]) + sq(c[1] - b[1]), sq(a[0] - c[0]) + sq(a[1] - c[1])});
  return orient2d(a, b, c) > 1e-6 * l2;
}

// Try moving v to (x, y): accepted when no star triangle inverts in the plane and the star's 3D
// min angles improve under the bound rule (see the header). Returns whether it moved.
struct StarQuality {
  double min = 180, sum = 0;
};

StarQuality starQuality(const Mesh& m, uint32_t v) {
  StarQuality q;
  for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) {
    const double a = m.minAngle[m.starTri[k]];
    q.min = std::min(q.min, a);
    q.sum += a;
  }
  return q;
}

bool tryMove(Mesh& m, uint32_t v, double x, double y, const LiftFn& lift, double bound, StarQuality& old) {
  const uint32_t* s = &m.starTri[m.starStart[v]];
  const size_t n = m.starStart[v + 1] - m.starStart[v];
  const double oldMin = old.min, oldSum = old.sum;
  // the floor: the bound, or the star's own min when it is below the bound (exactly: an
  // approximate min just under the bound may be an exact one on it)
  double floor = oldMin >= bound ? bound : oldMin;
  if (oldMin < bound && oldMin > bound - kApproxErrDeg) {
    double exact = 180;
    for (size_t i = 0; i < n; ++i) exact = std::min(exact, m.triMinExact(s[i]));
    if (exact >= bound) floor = bound;
  }
  Vec3 P;
  if (!lift(v, x, y, P)) return false;
  const Vec3 keep = m.pos[v];
  m.pos[v] = P;
  // the star's new min angles decide most candidates (most are refused)
  if (m.fresh.size() < n) m.fresh.resize(n);
  double* fresh = m.fresh.data();
  double newMin = 180, newSum = 0;
  for (size_t i = 0; i < n; ++i) {
    fresh[i] = m.triMin(s[i]);
    newMin = std::min(newMin, fresh[i]);
    newSum += fresh[i];
  }
  const bool better = oldMin < bound ? newMin > oldMin + 1e-9 : newSum > oldSum + 1e-9 * n;
  bool kept = newMin >= floor && better;
  // no star triangle may be inverted or a sliver in the plane: strictly positive, relative to
  // the triangle's size (checked after the angles, which refuse far more candidates)
  const double q[2] = {x, y};
  for (size_t i = 0; i < n && kept; ++i) {
    const uint32_t* t = &m.tri[3 * size_t(s[i])];
    const double* c[3];
    for (int k = 0; k < 3; ++k) c[k] = t[k] == v ? q : m.p(t[k]);
    kept = positiveInPlane(c[0], c[1], c[2]);
  }
  if (kept && floor == bound && newMin < bound + kApproxErrDeg)  // the bound at stake: exactly
    for (size_t i = 0; i < n && kept; ++i)
      if (fresh[i] < bound + kApproxErrDeg) kept = m.triMinExact(s[i]) >= bound;
  if (kept && m.guard) {
    const double ox = m.xy[2 * size_t(v)], oy = m.xy[2 * size_t(v) + 1];
    m.xy[2 * size_t(v)] = x, m.xy[2 * size_t(v) + 1] = y;
    kept = guardAccepts(m, s, n, norm(P - keep));
    m.xy[2 * size_t(v)] = ox, m.xy[2 * size_t(v) + 1] = oy;
  }
  if (!kept) {
    m.pos[v] = keep;
    return false;
  }
  m.xy[2 * size_t(v)] = x;
  m.xy[2 * size_t(v) + 1] = y;
  for (size_t i = 0; i < n; ++i) m.minAngle[s[i]] = fresh[i];
  rebucket(m, s, n);
  old = {newMin, newSum};
  return true;
}

// ODT position of v: the mean of its star triangles' circumcenters weighted by their areas.
bool odtTarget(const Mesh& m, uint32_t v, double out[2]) {
  double sx = 0, sy = 0, sw = 0;
  for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) {
    const uint32_t* t = &m.tri[3 * size_t(m.starTri[k])];
    const double *a = m.p(t[0]), *b = m.p(t[1]), *c = m.p(t[2]);
    double cc[2];
    if (!circumcenter(a, b, c, cc)) return false;
    const double w = 0.5 * orient2d(a, b, c);
    sx += w * cc[0];
    sy += w * cc[1];
    sw += w;
  }
  if (!(sw > 0)) return false;
  out[0] = sx / sw;
  out[1] = sy / sw;
  return true;
}

// Mean of the apexes of the equilateral triangles on the edges opposite v in its star: each
// triangle's own ideal place for v, averaged (the element-wise regularisation of GETMe smoothing,
// Vartziotis–Wipper 2009, in its simplest form). Unlike the ODT position it follows the local
// edge lengths, so it does not fight a graded mesh.
bool equilateralTarget(const Mesh& m, uint32_t v, double out[2]) {
  double sx = 0, sy = 0;
  int n = 0;
  for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) {
    const uint32_t* t = &m.tri[3 * size_t(m.starTri[k])];
    const int c = cornerOf(t, v);
    const double *a = m.p(t[kNext[c]]), *b = m.p(t[kPrev[c]]);
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    constexpr double h = 0.86602540378443864676;
    sx += 0.5 * (a[0] + b[0]) - h * dy;
    sy += 0.5 * (a[1] + b[1]) + h * dx;
    ++n;
  }
  if (n == 0) return false;
  out[0] = sx / n;
  out[1] = sy / n;
  return true;
}

// The sum of v's star's 3D min angles (minAngleDeg3Approx) with v lifted from planar (x, y);
// -infinity where the lift fails. Nothing changes.
double starSumAt(Mesh& m, uint32_t v, double x, double y, const LiftFn& lift) {
  Vec3 P;
  if (!lift(v, x, y, P)) return -INFINITY;
  const Vec3 keep = m.pos[v];
  m.pos[v] = P;
  double sum = 0;
  for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) sum += m.triMin(m.starTri[k]);
  m.pos[v] = keep;
  return sum;
}

// Move v to the first accepted candidate: the mean of the star's equilateral apexes, the ODT
// position, then a half step toward the first (three lifts at most; others tried gained too
// little for their cost: docs/decisions/0011). Each is computed only when the ones before it were
// rejected: the first is taken about half the time. A star still under the bound then gets a
// local search for a better min angle (8 directions, two step lengths relative to the star's
// shortest edge at v). One under `searchBelow` that none of the three improved gets a step up
// the gradient of its sum of 3D min angles instead (forward differences, two lifts; then up to
// three step lengths): the targets are planar averages, blind to how the surface bends them
// (OptimizeOptions::searchBelowDeg). Returns whether v moved.
bool improveVertex(Mesh& m, uint32_t v, const LiftFn& lift, double bound, double searchBelow) {
  std::vector<double>& xy = m.xy;
  const double x = xy[2 * size_t(v)], y = xy[2 * size_t(v) + 1];
  StarQuality q = starQuality(m, v);
  double eq[2], t[2] = {x, y};
  const bool eqOk = equilateralTarget(m, v, eq);
  bool moved = eqOk && tryMove(m, v, eq[0], eq[1], lift, bound, q);
  if (!moved && odtTarget(m, v, t)) moved = tryMove(m, v, t[0], t[1], lift, bound, q);
  if (!moved && eqOk) moved = tryMove(m, v, 0.5 * (x + eq[0]), 0.5 * (y + eq[1]), lift, bound, q);
  const bool search = q.min < bound, ascend = !search && !moved && q.min < searchBelow;
  if (!search && !ascend) return moved;
  double shortest = INFINITY;
  for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) {
    const uint32_t* t3 = &m.tri[3 * size_t(m.starTri[k])];
    for (int c = 0; c < 3; ++c)
      if (t3[c] != v) shortest = std::min(shortest, dmath::hypot(m.p(t3[c])[0] - xy[2 * size_t(v)], m.p(t3[c])[1] - xy[2 * size_t(v) + 1]));
  }
  if (ascend) {
    const double h = 0.05 * shortest;
    const double gx = starSumAt(m, v, x + h, y, lift) - q.sum, gy = starSumAt(m, v, x, y + h, lift) - q.sum;
    const double g = dmath::hypot(gx, gy);
    if (!(g > 0) || !std::isfinite(g)) return false;
    for (double step : {0.25, 0.1, 0.04})
      if (tryMove(m, v, x + step * shortest * gx / g, y + step * shortest * gy / g, lift, bound, q)) return true;
    return false;
  }
  for (double step : {0.25, 0.1})
    for (int d = 0; d < 8; ++d) {
      const double a = d * 0.78539816339744830962;
      const double cx = xy[2 * size_t(v)], cy = xy[2 * size_t(v) + 1];
      moved = tryMove(m, v, cx + step * shortest * dmath::cos(a), cy + step * shortest * dmath::sin(a), lift, bound, q) || moved;
    }
  return moved;
}

// Flip guard: with t0 = (c0, x, c1) and t1 = (c1, y, c0) in place of the current two, would the
// guard keep the flip? m is left as it was.
bool guardAcceptsFlip(Mesh& m, uint32_t t0, uint32_t t1, uint32_t c0, uint32_t x, uint32_t c1, uint32_t y) {
  if (!m.guard) return true;
  uint32_t* a = &m.tri[3 * size_t(t0)];
  uint32_t* b = &m.tri[3 * size_t(t1)];
  const std::array<uint32_t, 3> oa{a[0], a[1], a[2]}, ob{b[0], b[1], b[2]};
  a[0] = c0, a[1] = x, a[2] = c1;
  b[0] = c1, b[1] = y, b[2] = c0;
  const uint32_t ts[2] = {t0, t1};
  const bool ok = guardAccepts(m, ts, 2);
  std::copy(oa.begin(), oa.end(), a);
  std::copy(ob.begin(), ob.end(), b);
  return ok;
}

// Triangle adjacency: adj[3t + c] is the triangle across t's edge (v[c], v[c+1]), kNoTriangle on the
// boundary. Built from the stars once per patch (each edge at the vertex it leaves: the triangle
// of the star that enters that vertex from the edge's other end); flipPass keeps it current.
// Pre: the triangles are consistently oriented (a refinement's are).
void buildAdjacency(Mesh& m) {
  const size_t nt = m.tri.size() / 3, nv = m.starStart.size() - 1;
  m.adj.assign(3 * nt, kNoTriangle);
  struct Corner3 {
    uint32_t t, next, prev;
    int k;
  };
  std::vector<Corner3> star;
  for (uint32_t a = 0; a < nv; ++a) {
    star.clear();
    for (uint32_t i = m.starStart[a]; i < m.starStart[a + 1]; ++i) {
      const uint32_t t = m.starTri[i];
      const uint32_t* w = &m.tri[3 * size_t(t)];
      const int k = cornerOf(w, a);
      star.push_back({t, w[kNext[k]], w[kPrev[k]], k});
    }
    for (const Corner3& c : star)
      for (const Corner3& d : star)
        if (d.prev == c.next && d.t != c.t) {
          m.adj[3 * size_t(c.t) + c.k] = d.t;
          break;
        }
  }
}

// In triangle t, the adjacency slot that names `from` now names `to` (no-op for kNoTriangle).
inline void relink(Mesh& m, uint32_t t, uint32_t from, uint32_t to) {
  if (t == kNoTriangle) return;
  for (int c = 0; c < 3; ++c)
    if (m.adj[3 * size_t(t) + c] == from) {
      m.adj[3 * size_t(t) + c] = to;
      return;
    }
}

// One pass of flips: an interior edge flips when its quad is strictly convex in the plane, the
// smaller 3D min angle of its two triangles gets larger, and the new edge does not join two
// fixed vertices. Returns the number of flips.
// Edges are visited by triangle (each from its triangle of smaller index), only those with an
// end in `region`: an edge whose quad did not change since the last pass refused it would
// refuse it again. Only triangles with a vertex in `region` can have such an edge, and the
// second triangle of a flip, which the flip may give one (it is marked).
// Pre: m.adj and the stars are current.
size_t flipPass(Mesh& m, std::vector<uint8_t>& touched, const std::vector<uint8_t>& region, double bound) {
  const uint32_t nt = uint32_t(m.tri.size() / 3);
  std::vector<uint8_t> near(nt, 0);  // the second triangles of this pass's flips
  size_t flips = 0;
  for (uint32_t t0 = 0; t0 < nt; ++t0) {
    {
      const uint32_t* w = &m.tri[3 * size_t(t0)];
      if (!(near[t0] || region[w[0]] || region[w[1]] || region[w[2]])) continue;
    }
    for (int c = 0; c < 3; ++c) {
      const uint32_t t1 = m.adj[3 * size_t(t0) + c];
      if (t1 == kNoTriangle || t1 < t0) continue;
      uint32_t* v0 = &m.tri[3 * size_t(t0)];
      const uint32_t x = v0[c], y = v0[kNext[c]], c0 = v0[kPrev[c]];
      if (!(region[x] || region[y])) continue;
      if (m.fixed[x] && m.fixed[y] && keptEdge(*m.options, x, y)) continue;
      // t0 = (x, y, c0) counter-clockwise; t1 holds the edge as y -> x
      uint32_t* v1 = &m.tri[3 * size_t(t1)];
      const int d = cornerOf(v1, y);  // v1[d] = y, v1[d+1] = x
      if (v1[kNext[d]] != x) continue;                     // not a consistently oriented pair
      const uint32_t c1 = v1[kPrev[d]];
      if (c0 == c1) continue;
      // never a chord between two boundary vertices: the patch across their curves may draw the
      // same one (a stitch defect), and no move mends a triangle of three fixed vertices
      if (m.fixed[c0] && m.fixed[c1]) continue;
      // new triangles (c0, x, c1) and (c1, y, c0). Most edges do not flip: the first new angle
      // decides that for nearly all, so it is asked first
      const double before = std::min(m.minAngle[t0], m.minAngle[t1]);
      // with the valence operations: the change of the four vertices' squared deviations from
      // their ideal triangle counts; a flip that lowers it is kept at any angles not below the
      // bound, and a flip for the angles that raises it only where a triangle is below the
      // bound (else it would undo the first)
      int dv = 0;
      if (!m.deg.empty()) {
        auto d2 = [&](uint32_t v, int delta) { const int e = m.deg[v] + delta - m.ideal[v]; return e * e; };
        dv = d2(x, -1) + d2(y, -1) + d2(c0, 1) + d2(c1, 1) - d2(x, 0) - d2(y, 0) - d2(c0, 0) - d2(c1, 0);
      }
      const double valenceFloor = dv < 0 ? bound + kApproxErrDeg : INFINITY;
      const double n0 = minAngleDeg3Approx(m.pos[c0], m.pos[x], m.pos[c1]);
      if (!(n0 > before + 1e-6) && !(n0 >= valenceFloor)) continue;
      const double n1 = minAngleDeg3Approx(m.pos[c1], m.pos[y], m.pos[c0]);
      if (!(n1 > before + 1e-6) && !(n1 >= valenceFloor)) continue;
      if (const double n = std::min(n0, n1);
          !(n > before + 1e-6 && (dv <= 0 || before < bound + kApproxErrDeg)) && !(n >= valenceFloor))
        continue;
      // both must be strictly positive in the plane
      const double l2 = sq(m.p(c0)[0] - m.p(c1)[0]) + sq(m.p(c0)[1] - m.p(c1)[1]);
      if (!(orient2d(m.p(c0), m.p(x), m.p(c1)) > 1e-6 * l2) || !(orient2d(m.p(c1), m.p(y), m.p(c0)) > 1e-6 * l2)) continue;
      // near the bound, the rule on the exact angles (then no triangle at or above it goes below)
      if (std::min(n0, n1) < bound + kApproxErrDeg && before > bound - kApproxErrDeg &&
          !(std::min(minAngleDeg3(m.pos[c0], m.pos[x], m.pos[c1]), minAngleDeg3(m.pos[c1], m.pos[y], m.pos[c0])) >
            std::min(m.triMinExact(t0), m.triMinExact(t1)) + 1e-6))
        continue;
      if (!guardAcceptsFlip(m, t0, t1, c0, x, c1, y)) continue;
      // the quad's outer neighbours: (y, c0) and (c0, x) of t0, (x, c1) and (c1, y) of t1
      const uint32_t nYC0 = m.adj[3 * size_t(t0) + kNext[c]], nC0X = m.adj[3 * size_t(t0) + kPrev[c]];
      const uint32_t nXC1 = m.adj[3 * size_t(t1) + kNext[d]], nC1Y = m.adj[3 * size_t(t1) + kPrev[d]];
      m.minAngle[t0] = n0;
      m.minAngle[t1] = n1;
      v0[0] = c0, v0[1] = x, v0[2] = c1;
      v1[0] = c1, v1[1] = y, v1[2] = c0;
      m.adj[3 * size_t(t0)] = nC0X, m.adj[3 * size_t(t0) + 1] = nXC1, m.adj[3 * size_t(t0) + 2] = t1;
      m.adj[3 * size_t(t1)] = nC1Y, m.adj[3 * size_t(t1) + 1] = nYC0, m.adj[3 * size_t(t1) + 2] = t0;
      relink(m, nXC1, t1, t0);
      relink(m, nYC0, t0, t1);
      touched[x] = touched[y] = touched[c0] = touched[c1] = 1;
      if (!m.deg.empty()) --m.deg[x], --m.deg[y], ++m.deg[c0], ++m.deg[c1];
      {
        const uint32_t ts[2] = {t0, t1};
        rebucket(m, ts, 2);
      }
      near[t1] = 1;  // t1 > t0: visited later in this pass
      ++flips;
    }
  }
  return flips;
}

// Half-edge collapses of interior edges (u, w), u free, that bring the triangle counts of u, w
// and the two opposite vertices nearer their ideal (Mesh::ideal): a 5-valent pair between two
// 7-valent vertices becomes four regular ones, which no flip can do (valence-driven collapses
// and flips as in the regularization of Surazhsky and Gotsman, "Explicit surface remeshing",
// SGP 2003, and Botsch and Kobbelt 2004). u's triangles but the two on the edge take w for u;
// kept when they stay positive in the plane with their 3D min angles at or above `floor`, the
// guard keeps the change, the link condition holds (u and w share exactly the two opposite
// vertices) and no new edge joins two fixed vertices. The collapses of one pass touch disjoint
// stars; the triangles are compacted after it and each u is left without triangles (the caller
// drops such vertices). Only edges with an end in `region` are tried (as flipPass's). Returns
// the number of collapses; `touched` gets the changed stars' vertices.
size_t collapsePass(Mesh& m, std::vector<uint8_t>& touched, const std::vector<uint8_t>& region, double floor) {
  const size_t nt = m.tri.size() / 3, nv = m.xy.size() / 2;
  std::vector<uint8_t> locked(nv, 0), dead(nt, 0), reshaped(nt, 0);  // reshaped: took w for u
  std::vector<uint32_t> nu, nw, keep;
  auto neighbours = [&](uint32_t v, std::vector<uint32_t>& out) {
    out.clear();
    for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k)
      for (int c = 0; c < 3; ++c)
        if (const uint32_t z = m.tri[3 * size_t(m.starTri[k]) + c]; z != v) out.push_back(z);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  auto d2 = [&](uint32_t v, int delta) { const int e = m.deg[v] + delta - m.ideal[v]; return e * e; };
  size_t count = 0;
  for (uint32_t t0 = 0; t0 < nt; ++t0) {
    for (int c = 0; c < 3 && !dead[t0]; ++c) {
      const uint32_t t1 = m.adj[3 * size_t(t0) + c];
      if (t1 == kNoTriangle || t1 < t0 || dead[t1]) continue;
      const uint32_t* v0 = &m.tri[3 * size_t(t0)];
      const uint32_t x = v0[c], y = v0[kNext[c]], c0 = v0[kPrev[c]];
      if (locked[x] || locked[y] || !(region[x] || region[y])) continue;
      const uint32_t* v1 = &m.tri[3 * size_t(t1)];
      const int d = cornerOf(v1, y);
      if (v1[kNext[d]] != x) continue;
      const uint32_t c1 = v1[kPrev[d]];
      for (int side = 0; side < 2; ++side) {
        const uint32_t u = side ? x : y, w = side ? y : x;
        if (m.fixed[u]) continue;
        if (d2(w, m.deg[u] - 4) + d2(c0, -1) + d2(c1, -1) - d2(w, 0) - d2(c0, 0) - d2(c1, 0) - d2(u, 0) >= 0) continue;
        neighbours(u, nu);
        if (nu.size() != m.starStart[u + 1] - m.starStart[u]) continue;  // u's star is not a closed disk
        neighbours(w, nw);
        size_t common = 0;
        bool chord = false;
        for (const uint32_t z : nu) {
          if (std::binary_search(nw.begin(), nw.end(), z)) ++common;
          else if (z != w && m.fixed[w] && m.fixed[z]) chord = true;
        }
        if (common != 2 || chord) continue;
        // u's triangles with w for u
        keep.clear();
        double newMin = 180;
        bool ok = true;
        for (uint32_t k = m.starStart[u]; k < m.starStart[u + 1] && ok; ++k) {
          const uint32_t t = m.starTri[k];
          if (t == t0 || t == t1) continue;
          keep.push_back(t);
          const uint32_t* tv = &m.tri[3 * size_t(t)];
          const double* q[3];
          Vec3 P[3];
          for (int i = 0; i < 3; ++i) {
            const uint32_t z = tv[i] == u ? w : tv[i];
            q[i] = m.p(z);
            P[i] = m.pos[z];
          }
          ok = positiveInPlane(q[0], q[1], q[2]);
          newMin = std::min(newMin, minAngleDeg3Approx(P[0], P[1], P[2]));
        }
        if (!ok || !(newMin >= floor)) continue;
        // commit tentatively, then ask the guard about u's old star region
        for (const uint32_t t : keep)
          for (int i = 0; i < 3; ++i)
            if (m.tri[3 * size_t(t) + i] == u) m.tri[3 * size_t(t) + i] = w;
        if (!guardAccepts(m, &m.starTri[m.starStart[u]], m.starStart[u + 1] - m.starStart[u], keep.data(), keep.size())) {
          // undo: w was in none of them before (the link condition: only t0, t1 hold both)
          for (const uint32_t t : keep)
            for (int i = 0; i < 3; ++i)
              if (m.tri[3 * size_t(t) + i] == w) m.tri[3 * size_t(t) + i] = u;
          continue;
        }
        dead[t0] = dead[t1] = 1;
        for (const uint32_t t : keep) reshaped[t] = 1;
        m.deg[w] += m.deg[u] - 4;
        --m.deg[c0], --m.deg[c1];
        m.deg[u] = 0;
        locked[u] = locked[w] = touched[u] = touched[w] = 1;
        for (const uint32_t z : nu) locked[z] = touched[z] = 1;
        for (const uint32_t z : nw) locked[z] = touched[z] = 1;
        ++count;
        break;
      }
    }
  }
  if (count == 0) return 0;
  std::vector<uint32_t> renumbered(nt, kNoTriangle);
  size_t out = 0;
  for (size_t t = 0; t < nt; ++t) {
    if (dead[t]) continue;
    for (int i = 0; i < 3; ++i) m.tri[3 * out + i] = m.tri[3 * t + i];
    renumbered[t] = uint32_t(out++);
  }
  m.tri.resize(3 * out);
  m.cacheAll();
  m.buildStars();
  buildAdjacency(m);
  if (m.guard) {
    // the buckets of the triangles left, renumbered; the points of the dead ones and of those
    // that took w for u sorted again into the latter (they cover u's old star), not every point
    // into every triangle
    std::vector<uint32_t> head(out, kNoTriangle), changed;
    std::vector<double> err(out, 0.0);
    for (size_t t = 0; t < nt; ++t)
      if (const uint32_t n = renumbered[t]; n != kNoTriangle) {
        head[n] = m.head[t], err[n] = m.err[t];
        if (reshaped[t]) changed.push_back(n);
      }
    m.head.swap(head);
    m.err.swap(err);
    rebucketGuard(m, changed);
  }
  return count;
}

double meanMin(const Mesh& m) {
  const size_t nt = m.tri.size() / 3;
  if (nt == 0) return 0;
  double s = 0;
  for (size_t t = 0; t < nt; ++t) s += m.minAngle[t];
  return s / double(nt);
}

}  // namespace

bool keptEdge(const OptimizeOptions& o, uint32_t a, uint32_t b) {
  return !o.keptEdges.empty() && std::binary_search(o.keptEdges.begin(), o.keptEdges.end(), keptEdgeKey(a, b));
}

double minAngleDeg3(const Vec3& a, const Vec3& b, const Vec3& c) { return cornerDeg(smallestCorner(a, b, c)); }

double minAngleDeg3Approx(const Vec3& a, const Vec3& b, const Vec3& c) { return cornerDegApprox(smallestCorner(a, b, c)); }

OptimizeStats optimizePatch(std::vector<double>& xy, std::vector<uint32_t>& triangles, std::vector<Vec3>& pos,
                            const std::vector<uint8_t>& fixed, const LiftFn& lift, const OptimizeOptions& o,
                            const std::vector<uint8_t>& active0, const SurfaceSamples& guard, OptimizeCache* cache) {
  Mesh m{xy, triangles, pos, fixed, {}, {}, {}, {}, nullptr, {}, {}, {}, {}, {}, {}, {}};
  m.options = &o;
  OptimizeStats st;
  const size_t nt = triangles.size() / 3;
  // the previous call's min angles stand where no vertex moved since (the same positions give
  // the same values); its adjacency stands as the triangles are the same
  const size_t nv = xy.size() / 2;
  const bool reuse = cache && active0.size() == nv && cache->minAngle.size() == nt && cache->adjacency.size() == 3 * nt;
  std::vector<uint32_t> changedTris;  // with reuse: the triangles with an active vertex
  if (!guard.pos.empty()) m.guard = &guard;
  if (reuse) {
    m.minAngle.swap(cache->minAngle);
    m.adj.swap(cache->adjacency);
    for (size_t t = 0; t < nt; ++t) {
      const uint32_t* v = &triangles[3 * t];
      if (active0[v[0]] || active0[v[1]] || active0[v[2]]) {
        m.minAngle[t] = m.triMin(uint32_t(t));
        changedTris.push_back(uint32_t(t));
      }
    }
    if (cache->starStart.size() == nv + 1) {
      m.starStart.swap(cache->starStart);
      m.starTri.swap(cache->starTri);
    }
  } else {
    m.cacheAll();
  }
  if (m.guard) {
    if (reuse && cache->guardHead.size() == nt && cache->guardNext.size() == guard.pos.size() && cache->guardErr.size() == nt) {
      m.head.swap(cache->guardHead);
      m.next.swap(cache->guardNext);
      m.err.swap(cache->guardErr);
      rebucketGuard(m, changedTris);
    } else {
      bucketGuard(m);
    }
  }
  st.meanMinAngleBefore = st.meanMinAngleAfter = meanMin(m);
  double last = st.meanMinAngleBefore;
  // active set: a vertex is visited while it or a neighbour moved (or a flip touched its star)
  // in the previous pass
  std::vector<uint8_t> active = active0.size() == nv ? active0 : std::vector<uint8_t>(nv, 1), nextActive(nv, 0), changed(nv, 0);
  if (m.starStart.size() != nv + 1) m.buildStars();
  if (!reuse) buildAdjacency(m);
  if (o.valenceOperations) {
    m.deg.resize(nv);
    m.ideal.resize(nv);
    for (uint32_t v = 0; v < nv; ++v) {
      m.deg[v] = int(m.starStart[v + 1] - m.starStart[v]);
      m.ideal[v] = 6;
      if (!fixed[v]) continue;
      double sum = 0;  // the planar angle sum: the boundary's angle at a curve sample
      for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k) {
        const uint32_t* t = &triangles[3 * size_t(m.starTri[k])];
        const int c = cornerOf(t, v);
        const double *a = m.p(t[c]), *b = m.p(t[kNext[c]]), *d = m.p(t[kPrev[c]]);
        const double ux = b[0] - a[0], uy = b[1] - a[1], wx = d[0] - a[0], wy = d[1] - a[1];
        sum += dmath::atan2(std::abs(ux * wy - uy * wx), ux * wx + uy * wy);
      }
      m.ideal[v] = std::max(1, int(std::lround(sum * kRadToDeg / 60.0)));
    }
  }
  size_t flips = 0;
  for (int it = 0; it < o.maxIterations; ++it) {
    if (flips > 0) m.buildStars();  // moves keep the connectivity; flips change it
    std::fill(nextActive.begin(), nextActive.end(), 0);
    for (uint32_t v = 0; v < nv; ++v) {
      if (fixed[v] || !active[v] || m.starStart[v] == m.starStart[v + 1]) continue;
      if (!improveVertex(m, v, lift, o.minAngleDeg, o.searchBelowDeg)) continue;
      ++st.moves;
      for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k)
        for (int c = 0; c < 3; ++c) nextActive[m.tri[3 * size_t(m.starTri[k]) + c]] = 1;
    }
    // collapses with the flips, before them (a collapse leaves stars for the flips to even out),
    // over the same region
    if (!m.deg.empty() && !(it > 0 && it + 1 == o.maxIterations)) {
      for (size_t v = 0; v < nv; ++v) changed[v] = active[v] | nextActive[v];
      st.collapses += collapsePass(m, nextActive, changed, o.minAngleDeg + kApproxErrDeg);
    }
    // flips between passes give the next pass better stars; after the last of several passes a
    // flip pass would only mend what the moves left, for no measurable gain
    flips = 0;
    if (!(it > 0 && it + 1 == o.maxIterations)) {
      for (size_t v = 0; v < nv; ++v) changed[v] = active[v] | nextActive[v];
      flips = flipPass(m, nextActive, changed, o.minAngleDeg);
    }
    st.flips += flips;
    active.swap(nextActive);
    st.iterations = it + 1;
    const double now = meanMin(m);
    st.meanMinAngleAfter = now;
    if (now - last < o.tolerance * std::max(last, 1e-9)) break;
    last = now;
  }
  // passes aimed at the bound: the vertices of the triangles still below it, until none is left
  // or nothing moves or flips (the passes above stop on the mean's gain, while a few triangles
  // below the bound barely move the mean)
  for (int it = 0; it < o.boundPasses; ++it) {
    if (flips > 0) m.buildStars();
    std::fill(active.begin(), active.end(), 0);
    size_t bad = 0;
    for (size_t t = 0; t < nt; ++t)
      if (m.minAngle[t] < o.minAngleDeg) {
        ++bad;
        for (int c = 0; c < 3; ++c) active[triangles[3 * t + c]] = 1;
      }
    if (bad == 0) break;
    std::fill(nextActive.begin(), nextActive.end(), 0);
    size_t moves = 0;
    for (uint32_t v = 0; v < nv; ++v) {
      if (fixed[v] || !active[v] || m.starStart[v] == m.starStart[v + 1]) continue;
      if (!improveVertex(m, v, lift, o.minAngleDeg, o.searchBelowDeg)) continue;
      ++moves;
      for (uint32_t k = m.starStart[v]; k < m.starStart[v + 1]; ++k)
        for (int c = 0; c < 3; ++c) nextActive[m.tri[3 * size_t(m.starTri[k]) + c]] = 1;
    }
    for (size_t v = 0; v < nv; ++v) changed[v] = active[v] | nextActive[v];
    flips = flipPass(m, nextActive, changed, o.minAngleDeg);
    st.moves += moves;
    st.flips += flips;
    st.meanMinAngleAfter = meanMin(m);
    if (moves == 0 && flips == 0) break;
  }
  if (cache) {
    cache->minAngle.swap(m.minAngle);
    cache->adjacency.swap(m.adj);
    // the stars are current unless the last pass flipped
    if (flips > 0) m.starStart.clear(), m.starTri.clear();
    cache->starStart.swap(m.starStart);
    cache->starTri.swap(m.starTri);
    cache->guardHead.swap(m.head);
    cache->guardNext.swap(m.next);
    cache->guardErr.swap(m.err);
  }
  return st;
}

}  // namespace conformesh::optimization
