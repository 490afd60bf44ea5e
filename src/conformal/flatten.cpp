#include "conformal/flatten.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <map>
#include <string>

#include "conformal/intrinsic_triangulation.h"
#include "conformal/layout.h"
#include "conformal/triangle_geometry.h"
#include "core/detmath.h"
#include "planar/predicates.h"

namespace conformesh {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void distortion(const MeshBuffers& M, const std::vector<double>& uv, FlattenReport& R) {
  double sum = 0, mx = 1;
  size_t n = 0;
  for (size_t f = 0; f < M.triangleCount(); ++f) {
    const double* p[3];
    const double* w[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = &M.positions[3 * size_t(M.triangles[3 * f + k])];
      w[k] = &uv[2 * size_t(M.triangles[3 * f + k])];
    }
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = p[1][k] - p[0][k];
      e2[k] = p[2][k] - p[0][k];
    }
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double x2 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double y2 = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / l1;
    // J maps (l1, 0) -> w1 - w0 and (x2, y2) -> w2 - w0.
    const double u1 = w[1][0] - w[0][0], v1 = w[1][1] - w[0][1], u2 = w[2][0] - w[0][0], v2 = w[2][1] - w[0][1];
    const double a = u1 / l1, cc = v1 / l1;
    const double b = (u2 - a * x2) / y2, d = (v2 - cc * x2) / y2;
    const double E = 0.5 * (a + d), F = 0.5 * (a - d), G = 0.5 * (cc + b), H = 0.5 * (cc - b);
    const double Q = dmath::hypot(E, H), Rr = dmath::hypot(F, G);
    // the exact sign of the uv triangle, as written out (the sign of a·d − b·c, rounded, can differ)
    if (!(planar::orient2d(w[0], w[1], w[2]) > 0)) ++R.inputTrianglesInvertedInUv;
    const double s2 = std::fabs(Q - Rr);
    const double ratio = s2 > 0 ? (Q + Rr) / s2 : 1e300;
    if (!std::isfinite(ratio)) continue;
    sum += ratio;
    mx = std::max(mx, ratio);
    ++n;
  }
  R.angleDistortionMean = n ? sum / n : 1.0;
  R.angleDistortionMax = mx;
}

}  // namespace

std::vector<std::pair<uint32_t, double>> detectCorners(const MeshBuffers& patch, double threshold) {
  using namespace conformal;
  IntrinsicTriangulation T = buildIntrinsicTriangulation(patch);
  std::vector<double> angle, u(T.nV, 0.0);
  computeAngles(T, u, angle);
  std::vector<double> sum(T.nV, 0.0);
  for (int h = 0; h < 3 * T.nF; ++h) sum[T.vert[IntrinsicTriangulation::prev(h)]] += angle[h];
  size_t outer = 0;
  double best = -1;
  for (size_t k = 0; k < T.loops.size(); ++k) {
    double len = 0;
    for (int e : T.loopEdges[k]) len += dmath::exp(0.5 * T.lambda[e]);
    if (len > best) {
      best = len;
      outer = k;
    }
  }
  std::vector<std::pair<uint32_t, double>> corners;
  for (int v : T.loops[outer])
    if (std::fabs(sum[v] - kPi) > threshold) corners.emplace_back(uint32_t(v), sum[v]);
  return corners;
}

namespace {
FlatPatch flattenCompact(const MeshBuffers& patch, const FlattenOptions& options, const ProgressFn& progress);
}

namespace {
// e^{u_a} and e^{u_b} over the larger of the two: no overflow whatever u is
void edgeWeights(const std::vector<double>& u, uint32_t a, uint32_t b, double& ea, double& eb) {
  ea = dmath::exp(std::min(0.0, u[a] - u[b]));
  eb = dmath::exp(std::min(0.0, u[b] - u[a]));
}
}  // namespace

double edgeSurfaceParam(const std::vector<double>& u, uint32_t a, uint32_t b, double t) {
  double ea, eb;
  edgeWeights(u, a, b, ea, eb);
  return t * eb / ((1.0 - t) * ea + t * eb);
}

double edgePlanarParam(const std::vector<double>& u, uint32_t a, uint32_t b, double s) {
  double ea, eb;
  edgeWeights(u, a, b, ea, eb);
  return s * ea / (s * ea + (1.0 - s) * eb);
}

FlatPatch flatten(const MeshBuffers& patch, const FlattenOptions& options, ProgressFn progress) {
  // Vertices no face uses carry no metric: flatten without them and give them uv = (0, 0).
  const size_t nV = patch.vertexCount();
  std::vector<int> newId(nV, -1);
  for (uint32_t v : patch.triangles)
    if (v < nV) newId[v] = 0;
  size_t used = 0;
  for (size_t v = 0; v < nV; ++v)
    if (newId[v] == 0) newId[v] = int(used++);
  if (used == nV || patch.positions.size() != 3 * nV) return flattenCompact(patch, options, progress);
  MeshBuffers compact;
  std::vector<uint32_t> oldId(used);
  compact.positions.resize(3 * used);
  for (size_t v = 0; v < nV; ++v)
    if (newId[v] >= 0) {
      oldId[newId[v]] = uint32_t(v);
      for (int k = 0; k < 3; ++k) compact.positions[3 * newId[v] + k] = patch.positions[3 * v + k];
    }
  compact.triangles.resize(patch.triangles.size());
  for (size_t i = 0; i < patch.triangles.size(); ++i)
    compact.triangles[i] = patch.triangles[i] < nV ? uint32_t(newId[patch.triangles[i]]) : patch.triangles[i];
  FlattenOptions o = options;
  for (auto& c : o.corners)
    if (c.first < nV && newId[c.first] >= 0) c.first = uint32_t(newId[c.first]);
  for (auto& e : o.keepEdges)
    for (uint32_t& v : e)
      if (v < nV && newId[v] >= 0) v = uint32_t(newId[v]);
  FlatPatch P = flattenCompact(compact, o, progress);
  std::vector<double> uv(2 * nV, 0.0), u(nV, 0.0), pos(3 * nV, 0.0);
  for (size_t w = 0; w < used; ++w) {
    uv[2 * oldId[w]] = P.uv[2 * w];
    uv[2 * oldId[w] + 1] = P.uv[2 * w + 1];
    u[oldId[w]] = P.u[w];
    for (int k = 0; k < 3; ++k) pos[3 * oldId[w] + k] = P.layout.positions[3 * w + k];
  }
  P.uv = std::move(uv);
  P.u = std::move(u);
  P.layout.positions = std::move(pos);
  P.layout.uvs = P.uv;
  for (auto& t : P.layout.triangles) t = oldId[t];
  for (auto& loop : P.boundaryLoops)
    for (auto& v : loop) v = oldId[v];
  // The pull-back reports face indices (unchanged) and positions (same values): nothing to map.
  return P;
}

namespace {
// The circle solutions form a family: Möbius automorphisms of the disk map one solution to
// another, exactly (|f(p) - f(q)|^2 = |f'(p)| |f'(q)| |p - q|^2, circles stay circles and disk
// interiors stay inside, so the triangulation stays Delaunay and u changes by log |f'|). Pick
// the member whose 3D-area-weighted vertex centroid is the disk's centre (least distortion in
// practice), then restore the 3D area and lay out again.
// Complex |z|², |z|, z·w and z/w written out: the standard libraries round them differently
// (libstdc++'s std::norm squares cabs = glibc hypot, and its division is GCC's __divdc3; libc++
// sums squares, calls musl's hypot and scales by logb/scalbn), so native and WASM would differ.
using C = std::complex<double>;
inline double cnorm(const C& z) { return z.real() * z.real() + z.imag() * z.imag(); }
inline double cabs(const C& z) { return dmath::hypot(z.real(), z.imag()); }
inline C cmul(const C& z, const C& w) {
  return C(z.real() * w.real() - z.imag() * w.imag(), z.real() * w.imag() + z.imag() * w.real());
}
inline C cdiv(const C& z, const C& w) {
  const double n = cnorm(w);
  return C((z.real() * w.real() + z.imag() * w.imag()) / n, (z.imag() * w.real() - z.real() * w.imag()) / n);
}

void balanceMobius(const conformal::IntrinsicTriangulation& T, const MeshBuffers& patch, int outerLoop,
                   conformal::LayoutResult& L, std::vector<double>& u) {
  const auto& loop = T.loops[outerLoop];
  const size_t n = loop.size();
  if (n < 3) return;
  const C a(L.xy[2 * loop[0]], L.xy[2 * loop[0] + 1]), b(L.xy[2 * loop[n / 3]], L.xy[2 * loop[n / 3] + 1]),
      c(L.xy[2 * loop[2 * n / 3]], L.xy[2 * loop[2 * n / 3] + 1]);
  const C ba = b - a, ca = c - a;
  const double d = 2 * (ba.real() * ca.imag() - ba.imag() * ca.real());
  if (!(std::fabs(d) > 0)) return;
  const C centre = a + C((ca.imag() * cnorm(ba) - ba.imag() * cnorm(ca)) / d,
                         (ba.real() * cnorm(ca) - ca.real() * cnorm(ba)) / d);
  const double R = cabs(a - centre);
  std::vector<double> w(T.nV, 0.0);
  for (size_t f = 0; f < patch.triangleCount(); ++f) {
    const double* p0 = &patch.positions[3 * size_t(patch.triangles[3 * f])];
    const double* p1 = &patch.positions[3 * size_t(patch.triangles[3 * f + 1])];
    const double* p2 = &patch.positions[3 * size_t(patch.triangles[3 * f + 2])];
    const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const double A = 0.5 * dmath::hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
    for (int k = 0; k < 3; ++k) w[patch.triangles[3 * f + k]] += A / 3;
  }
  std::vector<C> z(T.nV);
  for (int v = 0; v < T.nV; ++v) z[v] = (C(L.xy[2 * v], L.xy[2 * v + 1]) - centre) / R;
  std::vector<double> du(T.nV, 0.0);
  for (int it = 0; it < 50; ++it) {
    C m(0, 0);
    double W = 0;
    for (int v = 0; v < T.nV; ++v) {
      m += w[v] * z[v];
      W += w[v];
    }
    m /= W;
    if (cabs(m) < 1e-10) break;
    if (cabs(m) > 0.5) m *= 0.5 / cabs(m);
    const double s = 1 - cnorm(m);
    for (int v = 0; v < T.nV; ++v) {
      const C q = 1.0 - cmul(std::conj(m), z[v]);
      du[v] += dmath::log(s) - 2 * dmath::log(cabs(q));
      z[v] = cdiv(z[v] - m, q);
    }
  }
  std::vector<double> u2 = u;
  for (int v = 0; v < T.nV; ++v) u2[v] += du[v];
  double a2 = 0, a3 = 0;
  for (double x : w) a3 += x;
  for (int f = 0; f < T.nF; ++f) {
    double lam[3], ang[3];
    for (int k = 0; k < 3; ++k) lam[k] = T.scaledLambda(3 * f + k, u2);
    conformal::anglesFromLogLengths(lam, ang);
    a2 += 0.5 * dmath::exp(0.5 * (lam[1] + lam[2])) * dmath::sin(ang[0]);
  }
  const double shift = 0.5 * dmath::log(a3 / a2);
  if (!std::isfinite(shift)) return;
  for (double& x : u2) x += shift;
  conformal::LayoutResult L2 = conformal::layoutFlat(T, u2);
  if (L2.invertedTriangles <= L.invertedTriangles && L2.boundaryCrossings <= L.boundaryCrossings) {
    L = std::move(L2);
    u = std::move(u2);
  }
}
}  // namespace

// What the pull-back is built from: the input's positions, its intrinsic triangulation, that
// triangulation made Delaunay (angular and horocyclic positions), the final one, its layout and u.
struct DeferredPullback {
  std::vector<double> positions;
  conformal::IntrinsicTriangulation Tin, TdAngular, Td, T;
  std::vector<double> xy, u;
};

void finishPullback(FlatPatch& flat) {
  if (!flat.deferred) return;
  using namespace conformal;
  const auto t = Clock::now();
  DeferredPullback& d = *flat.deferred;
  OverlayMap stage2 = buildOverlayMap(d.Tin, d.TdAngular, OverlayGeometry::Euclidean);
  OverlayMap stage1 = buildOverlayMap(d.Td, d.T, OverlayGeometry::Hyperbolic);
  flat.pullback = Pullback(std::move(d.positions), d.Tin.vert, std::move(d.xy), d.T.vert, std::move(d.u), std::move(stage1), std::move(stage2));
  flat.deferred.reset();
  flat.report.overlayCrossings = flat.pullback.crossings();
  flat.report.secondsOverlay = since(t);
  flat.report.seconds += flat.report.secondsOverlay;
}

namespace {
FlatPatch flattenCompact(const MeshBuffers& patch, const FlattenOptions& options, const ProgressFn& progress) {
  using namespace conformal;
  const auto t0 = Clock::now();
  IntrinsicTriangulation T = buildIntrinsicTriangulation(patch);
  if (!options.keepEdges.empty()) {
    std::map<std::pair<int, int>, int> edgeOf;
    for (int h = 0; h < 3 * T.nF; ++h) edgeOf.emplace(std::make_pair(T.vert[h], T.tip(h)), T.edge[h]);
    T.locked.assign(size_t(T.nE), 0);
    for (const auto& k : options.keepEdges) {
      const auto it = edgeOf.find({int(k[0]), int(k[1])});
      if (it == edgeOf.end() || T.twin[T.edgeHalf[it->second]] < 0)
        fail(Code::InvalidArgument, Stage::Flatten, "flatten: an edge to keep is no interior edge of the mesh");
      T.locked[size_t(it->second)] = 1;
    }
  }
  // Start from the intrinsic Delaunay triangulation of the input metric (Euclidean flips keep
  // the PL metric), as Gillespie–Springborn–Crane 2021: the conformal structure is then that of
  // the surface, not of its tessellation (a flat patch maps to itself however it is meshed).
  T.resetPositions(IntrinsicTriangulation::PositionKind::Angular);
  IntrinsicTriangulation Tin, TdAngular, Td;
  if (options.pullback) Tin = T;
  const long long euclideanFlips =
      options.flips ? conformal::flipToDelaunay(T, std::vector<double>(T.nV, 0.0), 200LL * T.nE + 10000, true) : 0;
  if (options.pullback) TdAngular = T;
  T.resetOrigins();
  T.resetPositions(IntrinsicTriangulation::PositionKind::Horocyclic);
  if (options.pullback) Td = T;

  FlowOptions fo;
  fo.boundary = options.boundary;
  fo.flips = options.flips;
  fo.tolerance = options.tolerance;
  fo.maxIterations = options.maxIterations;
  for (const auto& c : options.corners) {
    if (c.first >= patch.vertexCount())
      fail(Code::InvalidArgument, Stage::Flatten, "flatten: corner vertex " + std::to_string(c.first) + " out of range");
    fo.corners.emplace_back(int(c.first), c.second);
  }
  if (options.boundary == BoundaryCondition::Corners && options.corners.empty()) fo.boundary = BoundaryCondition::Circle;
  FlowResult flow = runRicciFlow(T, fo, progress);

  FlatPatch out;
  FlattenReport& R = out.report;
  R.iterations = flow.iterations;
  R.maxCurvatureError = flow.maxError;
  R.residuals = flow.residuals;
  R.flips = flow.flips;
  R.euclideanFlips = euclideanFlips;
  R.gaussBonnetError = flow.gaussBonnetError;
  R.boundaryLoops = int(T.loops.size());
  R.secondsFlow = since(t0);
  R.flowProfile = flow.profile;
  R.cornerAngleScale = flow.cornerAngleScale;

  // Normalize the scale: flat area = 3D area (Free keeps u = 0 on the boundary).
  std::vector<double> u = flow.u;
  if (options.boundary != BoundaryCondition::Free) {
    double a3 = 0, a2 = 0;
    for (size_t f = 0; f < patch.triangleCount(); ++f) {
      const double* p0 = &patch.positions[3 * size_t(patch.triangles[3 * f])];
      const double* p1 = &patch.positions[3 * size_t(patch.triangles[3 * f + 1])];
      const double* p2 = &patch.positions[3 * size_t(patch.triangles[3 * f + 2])];
      const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
      const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
      a3 += 0.5 * dmath::hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
    }
    for (int f = 0; f < T.nF; ++f) {
      double lam[3], ang[3];
      for (int k = 0; k < 3; ++k) lam[k] = T.scaledLambda(3 * f + k, u);
      anglesFromLogLengths(lam, ang);
      a2 += 0.5 * dmath::exp(0.5 * (lam[1] + lam[2])) * dmath::sin(ang[0]);  // angle 0 lies between edges 1, 2
    }
    const double c = 0.5 * dmath::log(a3 / a2);
    if (std::isfinite(c))
      for (double& x : u) x += c;
  }
  if (progress && !progress(Stage::Flatten, 0.85)) fail(Code::Cancelled, Stage::Flatten, "flatten: cancelled");

  const auto t1 = Clock::now();
  LayoutResult L = layoutFlat(T, u);
  if (fo.boundary == BoundaryCondition::Circle && options.balanceMobius && L.invertedTriangles == 0)
    balanceMobius(T, patch, flow.outerLoop, L, u);
  R.secondsLayout = since(t1);
  R.invertedTriangles = L.invertedTriangles;
  R.boundaryCrossings = L.boundaryCrossings;
  for (const auto& c : L.crossingEdges) R.boundaryCrossingEdges.push_back({uint32_t(c[0]), uint32_t(c[1]), uint32_t(c[2]), uint32_t(c[3])});
  R.layoutLengthError = L.maxEdgeLengthError;
  if (L.invertedTriangles > 0 || L.boundaryCrossings > 0 || !(L.maxEdgeLengthError <= 1e-3)) {
    std::string why = scaleDiagnosis(T, u, fo.boundary);
    // every triangle in place and every length kept, yet the border crosses itself: the map is
    // right and the patch winds further than one sheet of the plane holds (a ramp of more than
    // a turn); no precision mends that
    if (why.empty() && L.invertedTriangles == 0 && L.maxEdgeLengthError <= 1e-3)
      why = "the flat map is valid triangle by triangle but its border overlaps itself (the patch winds around more "
            "than the plane holds): split the patch";
    R.invalidLayout = "flatten: the layout has " + std::to_string(L.invertedTriangles) + " inverted triangles, " +
                      std::to_string(L.boundaryCrossings) + " boundary crossings and a relative edge length error of " +
                      std::to_string(L.maxEdgeLengthError) + ": " +
                      (why.empty() ? std::string("the area distortion may be too large for double precision: try the free boundary or split the patch") : why);
    if (options.requireValidLayout) fail(Code::NumericalFailure, Stage::Flatten, R.invalidLayout);
  }

  out.uv = L.xy;
  out.u = u;
  out.layout.positions.resize(3 * size_t(T.nV));
  for (int v = 0; v < T.nV; ++v) {
    out.layout.positions[3 * v] = L.xy[2 * v];
    out.layout.positions[3 * v + 1] = L.xy[2 * v + 1];
    out.layout.positions[3 * v + 2] = 0.0;
  }
  out.layout.triangles.assign(T.vert.begin(), T.vert.end());
  out.layout.uvs = L.xy;
  {
    std::vector<std::vector<uint32_t>> loops;
    loops.emplace_back(T.loops[flow.outerLoop].begin(), T.loops[flow.outerLoop].end());
    for (size_t k = 0; k < T.loops.size(); ++k)
      if (int(k) != flow.outerLoop) loops.emplace_back(T.loops[k].begin(), T.loops[k].end());
    out.boundaryLoops = std::move(loops);
  }
  double umin = 1e300, umax = -1e300;
  for (double x : u) {
    umin = std::min(umin, x);
    umax = std::max(umax, x);
  }
  R.areaDistortionMin = dmath::exp(2 * umin);
  R.areaDistortionMax = dmath::exp(2 * umax);
  R.areaDistortionRange = dmath::exp(2 * (umax - umin));
  distortion(patch, out.uv, R);
  if (progress && !progress(Stage::Flatten, 0.9)) fail(Code::Cancelled, Stage::Flatten, "flatten: cancelled");

  R.seconds = since(t0);  // finishPullback adds the overlay's time
  if (options.pullback) {
    out.deferred = std::make_shared<DeferredPullback>(
        DeferredPullback{patch.positions, std::move(Tin), std::move(TdAngular), std::move(Td), std::move(T), std::move(L.xy), std::move(u)});
    if (!options.deferPullback) finishPullback(out);
  }
  if (progress && !progress(Stage::Flatten, 1.0)) fail(Code::Cancelled, Stage::Flatten, "flatten: cancelled");
  return out;
}
}  // namespace

}  // namespace conformesh
