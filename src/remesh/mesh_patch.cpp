#include "remesh/mesh_patch.h"
#include "core/constants.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/detmath.h"
#include "core/hilbert.h"
#include "planar/predicates.h"
#include "planar/refine.h"
#include "remesh/curve_samples.h"
#include "remesh/split_below_bound.h"

namespace conformesh::pipeline {
namespace {

//! x² as one product (std::pow(x, 2) goes through libm in some builds).
inline double sq(double x) { return x * x; }
// Degrees added to the angle bound for the planar refinement (see meshPatch). Each degree above
// 30 costs the off-center refinement steeply in graded regions (its quality splits cascade there:
// ChineseDragon-10kv 1.25 → 1.05 times its estimate from 2° to 1° with 45° off-centers), and the
// optimization lifts the triangles the lift's distortion takes below the bound
// (docs/decisions/0045).
constexpr double kPlanarAngleMargin = 1.0;
// The margin of the triangles whose three vertices are samples, which the optimization cannot
// move: the whole distortion of the lift (≤ ~2°, docs/decisions/0010).
constexpr double kFixedTriangleMargin = 2.0;
// Highest bound of the planar refinement but for the triangles the optimization cannot move:
// above it the off-center refinement's count grows steeply (camelhead at 34°: 1.76 times its
// count at 32°), while the optimization lifts the other triangles to a higher 3D bound.
constexpr double kPlanarMaxDeg = 32.0;
// A 3D bound whose planar bound (with its margin) is above kPlanarMaxDeg: the refinement leaves
// the free triangles to the optimization there.
inline bool aboveMaxPlanar(double minAngle) { return minAngle + kPlanarAngleMargin > kPlanarMaxDeg; }
// Passes of the optimization over the triangles below the bound when the planar refinement
// gives them less than the bound and its margin (measured: a bound of 35 held on 3 more models
// with them, in fewer certificate rounds).
constexpr int kBoundPasses = 8;
// Optimization passes added to the asked ones there: what they lift to the bound the certificate
// rounds need not re-mesh (at 35°, two rather than one: the mean min angle 0.1-0.3° higher on
// every model of ../shared/data, ChineseDragon-10kv's certificate rounds 4 -> 1, its time 2.9 ->
// 1.8 times the 30° run's; bench/results/deg35-2026-12-05-passes.md).
constexpr int kExtraPassesAbove = 2;
// There too, the stars whose smallest 3D angle is less than this above the bound get a step up
// the gradient of their 3D angles when the optimizer's targets fail (OptimizeOptions::
// searchBelowDeg; docs/decisions/0053).
constexpr double kSearchAboveBoundDeg = 10.0;
// Angle (degrees) at the new vertex of the triangle an off-center (Üngör 2009) makes with the
// shortest edge of a bad triangle: well above the bound, so graded bands do not stay at it, while
// the new vertex stays 1 / (2 sin 25°) ≈ 1.18 edges away and insertion radii still grow
// (docs/decisions/0012-offcenter-apex.md; 50° rather than 45° with the 1° margin, 0045).
constexpr double kOffcenterApexDeg = 50.0;
// The same above kPlanarMaxDeg (a 3D bound of 35°): nearer equilateral there, where the
// optimization must lift every free triangle above the bound and its moves and valence
// operations start from the refinement's shapes (mean min angle at 35° on the 19 models of
// ../shared/data 51.5-53.5° with both, 50.4-51.7° at 45° without the valence operations;
// docs/decisions/0035).
constexpr double kOffcenterApexHighDeg = 50.0;
// Shortest boundary piece a patch refinement may split, in Surface::splitFloorLength (the
// sizing's smallest edge length, target/10 by default), on the surface: far below any size the
// output can mean.
// Near a small angle between two curves the refinements of the two sides can keep splitting
// each other's segments (each side's concentric shells are not the other's) down to 1e-9 of the
// diagonal, every new triangle there below the bound (docs/decisions/0002).
constexpr double kMinSegmentFactor = 1e-2;
// Times a patch's boundary chords may be split where they cross before refinement gives up.
constexpr int kCrossingRepairs = 8;

// Vertex v of m becomes vertex id[v] (kNone: dropped) of a mesh with `count` vertices; the
// triangles and edges follow.
void renumberVertices(planar::PlanarMesh& m, const std::vector<uint32_t>& id, size_t count) {
  std::vector<double> points(2 * count), param(count);
  std::vector<int32_t> segment(count);
  for (size_t v = 0; v < id.size(); ++v) {
    if (id[v] == kNone) continue;
    points[2 * size_t(id[v])] = m.points[2 * v];
    points[2 * size_t(id[v]) + 1] = m.points[2 * v + 1];
    segment[id[v]] = m.vertexSegment[v];
    param[id[v]] = m.vertexParam[v];
  }
  m.points.swap(points);
  m.vertexSegment.swap(segment);
  m.vertexParam.swap(param);
  for (uint32_t& v : m.triangles) v = id[v];
  for (uint32_t& v : m.edges) v = id[v];
}

// Remove the vertices from index `keep` on that no triangle uses (a required point that a later
// boundary split left outside the domain, or one inserted twice), renumbering the rest: every
// vertex of a patch's meshing becomes an output vertex.
void dropUnusedPoints(planar::PlanarMesh& m, size_t keep) {
  const size_t nv = m.vertexCount();
  std::vector<uint32_t> id(nv, kNone);
  for (uint32_t v : m.triangles) id[v] = 0;
  size_t next = 0;
  bool any = false;
  for (size_t v = 0; v < nv; ++v) {
    if (v < keep || id[v] == 0) id[v] = uint32_t(next++);
    else any = true;
  }
  if (any) renumberVertices(m, id, next);
}

// Renumber the vertices from index `keep` on along a Hilbert curve over their planar positions,
// and order the triangles by their smallest vertex (then the others): the refinement leaves them
// in the order its queue inserted them, all over the patch, while the lift, the optimization and
// the certificate visit vertices by index and a vertex's star by its triangles. Neighbours in
// memory are then neighbours in the plane (the optimization's stars, lifts and guard).
void spatialOrder(planar::PlanarMesh& m, size_t keep) {
  const size_t nv = m.vertexCount();
  if (nv <= keep + 1) return;
  std::vector<uint32_t> refined(nv - keep);
  std::iota(refined.begin(), refined.end(), uint32_t(keep));
  const std::vector<uint32_t> order = hilbertOrder(m.points.data(), refined);
  std::vector<uint32_t> id(nv);
  for (size_t v = 0; v < keep; ++v) id[v] = uint32_t(v);
  for (size_t i = 0; i < order.size(); ++i) id[order[i]] = uint32_t(keep + i);
  renumberVertices(m, id, nv);
  // triangles: rotated to start at their smallest vertex (orientation kept), then sorted
  const size_t nt = m.triangleCount();
  std::vector<std::array<uint32_t, 3>> tris(nt);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* x = &m.triangles[3 * t];
    const int r = x[0] <= x[1] && x[0] <= x[2] ? 0 : (x[1] <= x[2] ? 1 : 2);
    tris[t] = {x[r], x[(r + 1) % 3], x[(r + 2) % 3]};
  }
  std::sort(tris.begin(), tris.end());
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) m.triangles[3 * t + k] = tris[t][k];
}

// Largest distance of a patch's input vertices from the plane through their centroid normal to
// the patch's area-weighted normal (infinity when that normal vanishes: a closed-up patch).
double slabHalfWidth(const F::PatchMesh& pm) {
  const auto& P = pm.mesh.positions;
  const size_t nv = pm.mesh.vertexCount();
  if (nv == 0) return INFINITY;
  const auto at = [&](uint32_t v) { return vec3At(P, v); };
  Vec3 n{0, 0, 0}, c{0, 0, 0};
  for (size_t t = 0; t < pm.mesh.triangleCount(); ++t) {
    const uint32_t* v = &pm.mesh.triangles[3 * t];
    n = n + cross(at(v[1]) - at(v[0]), at(v[2]) - at(v[0]));
  }
  for (uint32_t v = 0; v < nv; ++v) c = c + at(v);
  c = c * (1.0 / double(nv));
  const double ln = norm(n);
  if (!(ln > 0)) return INFINITY;
  n = n * (1.0 / ln);
  double w = 0;
  for (uint32_t v = 0; v < nv; ++v) w = std::max(w, std::abs(dot(n, at(v) - c)));
  return std::isfinite(w) ? w : INFINITY;
}

// Fewer than 3 samples on the boundary loop, or all of them on one line (relative to their
// spread).
bool degenerateBoundary(const std::vector<BoundaryPoint>& bp) {
  const size_t n = loopPointCount(bp);  // the loop's points come first
  if (n < 3) return true;
  double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
  for (size_t i = 0; i < n; ++i) minx = std::min(minx, bp[i].x), maxx = std::max(maxx, bp[i].x), miny = std::min(miny, bp[i].y), maxy = std::max(maxy, bp[i].y);
  const double span = std::max(maxx - minx, maxy - miny);
  if (!(span > 0)) return true;
  // the point farthest from the line through the first point and the point farthest from it
  size_t far = 0;
  double d2 = 0;
  for (size_t i = 1; i < n; ++i) {
    double dd = sq(bp[i].x - bp[0].x) + sq(bp[i].y - bp[0].y);
    if (dd > d2) d2 = dd, far = i;
  }
  double ex = bp[far].x - bp[0].x, ey = bp[far].y - bp[0].y, l = std::sqrt(d2), off = 0;
  for (size_t i = 0; i < n; ++i) off = std::max(off, std::abs((bp[i].x - bp[0].x) * ey - (bp[i].y - bp[0].y) * ex) / l);
  return off < 1e-6 * span;
}

// A patch's planar domain: the closed polygon through its loop's points, in order, then the
// segments of its inner curves (segment i of the PSLG is addSplitSample's segment i).
planar::Pslg patchPslg(const std::vector<BoundaryPoint>& bp, const std::vector<InnerSegment>& inner) {
  planar::Pslg pslg;
  for (const auto& b : bp) pslg.points.insert(pslg.points.end(), {b.x, b.y});
  const uint32_t loop = uint32_t(loopPointCount(bp));
  for (uint32_t i = 0; i < loop; ++i) pslg.segments.insert(pslg.segments.end(), {i, uint32_t((i + 1) % loop)});
  for (const InnerSegment& sg : inner) pslg.segments.insert(pslg.segments.end(), {sg.a, sg.b});
  return pslg;
}

// The segments of a patch's domain that cross another one (or fold back onto a segment they
// share an end with), by exact orientation tests over all pairs: only used when refinement rejected the
// polygon, which is rare.
std::vector<uint32_t> crossingSegments(const planar::Pslg& pslg) {
  const uint32_t n = uint32_t(pslg.segments.size() / 2);
  const double* P = pslg.points.data();
  auto pt = [&](uint32_t s, int end) { return P + 2 * pslg.segments[2 * s + end]; };
  auto sgn = [](double x) { return (x > 0) - (x < 0); };
  std::vector<uint8_t> bad(n, 0);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j) {
      const double *a = pt(i, 0), *b = pt(i, 1), *c = pt(j, 0), *d = pt(j, 1);
      const bool adjacent = pslg.segments[2 * i + 1] == pslg.segments[2 * j] || pslg.segments[2 * j + 1] == pslg.segments[2 * i];
      if (adjacent) {
        // shared endpoint m, far ends x (of i) and y (of j): they fold back when collinear and
        // on the same side of m
        const bool iFirst = pslg.segments[2 * i + 1] == pslg.segments[2 * j];
        const double* m = iFirst ? b : a;
        const double* x = iFirst ? a : b;
        const double* y = iFirst ? d : c;
        if (planar::orient2d(x, m, y) == 0 && (x[0] - m[0]) * (y[0] - m[0]) + (x[1] - m[1]) * (y[1] - m[1]) > 0) bad[i] = bad[j] = 1;
        continue;
      }
      const int o1 = sgn(planar::orient2d(a, b, c)), o2 = sgn(planar::orient2d(a, b, d));
      const int o3 = sgn(planar::orient2d(c, d, a)), o4 = sgn(planar::orient2d(c, d, b));
      if (o1 * o2 > 0 || o3 * o4 > 0) continue;
      if (o1 == 0 && o2 == 0) {  // collinear: crossing only when the spans overlap
        const int k = std::abs(b[0] - a[0]) >= std::abs(b[1] - a[1]) ? 0 : 1;
        const double lo1 = std::min(a[k], b[k]), hi1 = std::max(a[k], b[k]), lo2 = std::min(c[k], d[k]), hi2 = std::max(c[k], d[k]);
        if (hi1 < lo2 || hi2 < lo1) continue;
      }
      bad[i] = bad[j] = 1;
    }
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < n; ++i)
    if (bad[i]) out.push_back(i);
  return out;
}

// Lift a planar point onto the input surface. The PSLG's boundary segments are chords of the
// flattened boundary (between curve samples), so a refinement vertex near a concave stretch of
// boundary can lie just outside the flattened patch: it is lifted from the nearest point of the
// flattened boundary polyline instead (on the input's boundary curve, within the chord's sagitta).
// hintFace: a face of the final layout near (x, y) to start the point location from (-1: none).
bool liftPoint(const PatchWork& w, double x, double y, PullbackPoint& q, int hintFace = -1) {
  const Pullback& pb = w.flat.pullback;
  if (pb.locate(x, y, hintFace, q, 1e-9)) return true;
  const auto& loop = w.pm.boundaryLoops[0];
  const auto& uv = w.flat.uv;
  double best = INFINITY, bx = x, by = y;
  for (const auto& h : loop) {
    uint32_t a = w.pm.mesh.triangles[3 * h.face + h.corner], b = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
    double ex = uv[2 * b] - uv[2 * a], ey = uv[2 * b + 1] - uv[2 * a + 1], l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? std::clamp(((x - uv[2 * a]) * ex + (y - uv[2 * a + 1]) * ey) / l2, 0.0, 1.0) : 0.0;
    double px = uv[2 * a] + t * ex, py = uv[2 * a + 1] + t * ey, d = dmath::hypot(px - x, py - y);
    if (d < best) best = d, bx = px, by = py;
  }
  return std::isfinite(best) && pb.locate(bx, by, q, 1e-6);
}

// RefineOptions::apexOf and chainOf for a patch's PSLG (its boundary points first, then
// `points` in all): a boundary point on a curve that ends at an input corner below the bound
// (Meshing::smallCorner) whose wedge in this patch is below it (boundDeg) in 3D or in the plane
// has that corner's boundary point as its apex and the curve as its chain;
// on a curve between two such corners, with `nearest` the corner nearer in the plane, else the one
// at the curve's first end (which leaves the other wedge to the refinement). The triangles across such a wedge are then left as it forces them, as the 3D certificate
// leaves them (certificate.h): refining them only splits the sides closer to the corner, and the
// patches across take up each split, round after round.
void cornerChains(const Surface& surf, const Meshing& m, const PatchWork& w, const std::vector<BoundaryPoint>& bp,
                  size_t points, bool nearest, double boundDeg, std::vector<uint32_t>& apexOf,
                  std::vector<uint32_t>& chainOf) {
  apexOf.clear();
  chainOf.clear();
  const F::CurveMesh& cm = m.samples.cm;
  const auto corner = [&](uint32_t sample) {
    const uint32_t v = cm.samples[sample].vertex;
    return v != kNone && v < m.smallCorner.size() && m.smallCorner[v];
  };
  const auto& loop = w.pm.boundaryLoops[0];
  const size_t loopPoints = loopPointCount(bp);  // the corners' wedges are on the loop
  // The patch's own wedge at a boundary point, in 3D (the angle sum of its faces at that sub
  // vertex) and in the plane (the polygon's inner angle there). A small corner can have wider
  // wedges beside its small one (two curves at 31° where another pair meets at 22°): where such a
  // wedge is at least the bound on both sides of the map, its triangles are held to the bound as
  // at any other corner, not left as forced.
  const auto smallWedge = [&](uint32_t i) {
    const auto& h = loop[bp[i].loopPos];
    const uint32_t sub = w.pm.mesh.triangles[3 * h.face + h.corner];
    double sum = 0;
    for (uint32_t f = 0; f < w.pm.faceInput.size(); ++f)
      for (int c = 0; c < 3; ++c)
        if (w.pm.mesh.triangles[3 * f + c] == sub) sum += surf.g.cornerAngle(w.pm.faceInput[f], c);
    if (sum * 180.0 / kPi < boundDeg) return true;
    const size_t n = loopPoints;
    const BoundaryPoint &a = bp[(i + n - 1) % n], &b = bp[i], &c = bp[(i + 1) % n];
    double area2 = 0;  // twice the polygon's signed area: the inner side of the boundary
    for (size_t k = 0; k < n; ++k) area2 += bp[k].x * bp[(k + 1) % n].y - bp[(k + 1) % n].x * bp[k].y;
    const double ux = c.x - b.x, uy = c.y - b.y, vx = a.x - b.x, vy = a.y - b.y;
    double inner = dmath::atan2(ux * vy - uy * vx, ux * vx + uy * vy);  // from the next point to the previous, counterclockwise
    if (area2 < 0) inner = -inner;
    if (inner < 0) inner += 2 * kPi;
    return inner * 180.0 / kPi < boundDeg;
  };
  std::vector<uint32_t> apexSamples;  // the small corners on this patch's boundary, and their boundary points
  std::vector<uint32_t> apexPoint;
  for (uint32_t i = 0; i < loopPoints; ++i)
    if (corner(bp[i].sample) && std::find(apexSamples.begin(), apexSamples.end(), bp[i].sample) == apexSamples.end() &&
        smallWedge(i))
      apexSamples.push_back(bp[i].sample), apexPoint.push_back(i);
  if (apexSamples.empty()) return;
  apexOf.assign(points, planar::kNoApex);
  chainOf.assign(points, planar::kNoApex);
  for (uint32_t i = 0; i < loopPoints; ++i) {
    const F::CurveSample& smp = cm.samples[bp[i].sample];
    if (smp.vertex != kNone && surf.seg.vertexCorner[smp.vertex]) continue;  // a corner ends every chain
    const auto& h = loop[bp[i].loopPos];
    const uint32_t c = surf.seg.edgeCurve[surf.g.faceEdges[w.pm.faceInput[h.face]][h.corner]];
    if (c == kNone) continue;
    const auto& ids = cm.curveSamples[c];
    double best = INFINITY;  // squared planar distance to the apex taken
    for (uint32_t end : {ids.front(), ids.back()}) {
      const auto it = std::find(apexSamples.begin(), apexSamples.end(), end);
      if (it == apexSamples.end()) continue;
      const uint32_t a = apexPoint[size_t(it - apexSamples.begin())];
      const double d = sq(bp[a].x - bp[i].x) + sq(bp[a].y - bp[i].y);
      if (!(d < best)) continue;
      best = d;
      apexOf[i] = a;
      chainOf[i] = c;
      if (!nearest) break;
    }
  }
}

// Refine patch p from its boundary points bp and lift the new vertices, writing nothing but
// `out` (see refineApart). False, with the refinement's error in `crossing`, when the chords
// between bp cross (the refinement rejects the polygon: InvalidPslg); other errors are thrown.
bool refineAndLift(const Surface& surf, const RemeshOptions& opt, const Meshing& m, uint32_t p, bool splitSegments,
                   const std::vector<BoundaryPoint>& bp, const std::vector<InnerSegment>& inner, PatchMeshing& out,
                   Status& crossing) {
  const Clock::time_point start = Clock::now();
  const PatchWork& w = *m.patches[p];
  planar::Pslg pslg = patchPslg(bp, inner);
  pslg.points.insert(pslg.points.end(), w.requiredPoints.begin(), w.requiredPoints.end());
  planar::RefineOptions ro;
  // Diametral lenses: far fewer segment splits, so fewer samples a neighbour must take up and
  // fewer rounds. The planar bound has a margin over the 3D one for the small angle distortion
  // of the lift (the map is conformal only in the discrete sense; measured: ≤ ~1.5° on the
  // models in ../shared/data with the free boundary).
  ro.diametralLens = true;
  ro.splitSegments = splitSegments;
  // The triangles whose three vertices are boundary samples (RefineOptions::
  // segmentTriangleMinAngleDeg), which the optimization cannot move, get the whole margin of the
  // lift; above kPlanarMaxDeg the bound holds in the plane only for them, and the optimization
  // lifts the others in 3D (optimizeMesh).
  ro.minAngleDeg = std::min(opt.minAngle + kPlanarAngleMargin, kPlanarMaxDeg);
  ro.segmentTriangleMinAngleDeg = opt.minAngle + kFixedTriangleMargin;
  // off-center factor for the apex angle: the off-center of factor f sits f / (2 tan(θ/2))
  // shortest-edge lengths from that edge, where it sees the edge under 2 atan(tan(θ/2) / f)
  // (refine.h); never above the planar default (bounds near 45° would otherwise get it)
  if (ro.minAngleDeg > 0)
    ro.offcenterFactor = std::min(0.95, dmath::tan(0.5 * ro.minAngleDeg * kPi / 180) /
                                            dmath::tan(0.5 * (aboveMaxPlanar(opt.minAngle) ? kOffcenterApexHighDeg : kOffcenterApexDeg) * kPi / 180));
  // Boundary pieces shorter than this are not split: far below any size the output can mean,
  // and above the resolution at which two splits of one input edge are told apart (the sample
  // dedupe in addSplitSample); refinements that keep splitting each other's segments stop here.
  // A planar length l is l / s on the surface where the planar/3D scale is s: with the patch's
  // smallest scale the limit is at most kMinSegmentFactor · splitFloorLength on the surface
  // anywhere in the patch (less where the scale is larger), so it never stops a split the sizing
  // asks for.
  ro.minSegmentLength = kMinSegmentFactor * surf.splitFloorLength * *std::min_element(w.scaleSub.begin(), w.scaleSub.end());
  // Longest-edge bound of the refinement vs the mean edge length it gives: calibrated so the
  // mean output edge length in flat regions is the target.
  const double kSizeFactor = 1.3;
  // The size at a planar point: h and the planar/3D scale interpolated in the face of the
  // flattened triangulation that contains it (it has the sub-mesh's vertices), found by a walk
  // from the face of the previous query (the refinement asks about nearby points in a row).
  const Pullback& pb = w.flat.pullback;
  int sizingFace = -1;
  const SpotField spots(w.spots);
  ro.sizing = [&](double x, double y) {
    int fv[3];
    double b[3];
    if (!pb.locateLayout(x, y, sizingFace, fv, b, 1e-6)) return double(INFINITY);
    double h = 0, s = 0;
    for (int c = 0; c < 3; ++c) {
      h += b[c] * w.hSub[uint32_t(fv[c])];
      s += b[c] * w.scaleSub[uint32_t(fv[c])];
    }
    return spots.size(x, y, kSizeFactor * h * s);
  };
  double area3 = 0;
  for (uint32_t f : w.pm.faceInput) area3 += surf.g.faceArea(f);
  ro.maxInsertions = size_t(std::min(4e7, 50.0 * area3 / (surf.sizing.minLength * surf.sizing.minLength) + 1e5));
  // the nearer corner of a curve between two is the right one at any bound; at 30° and below the
  // first one is kept for now, as their outputs are (the nearer one there: 5 models change, 7-10 %
  // fewer triangles on 4, bench/results/deg35-2026-12-03.md)
  cornerChains(surf, m, w, bp, pslg.points.size() / 2, aboveMaxPlanar(opt.minAngle), opt.minAngle, ro.apexOf,
               ro.chainOf);
  planar::RefineResult rr;
  try {
    rr = planar::refinePslg(pslg, ro);
  } catch (const Error& e) {
    if (e.code() != Code::InvalidPslg) throw;
    crossing = e.status();
    return false;
  }
  if (!rr.status.ok()) fail(rr.status.code, Stage::Refine, "patch " + std::to_string(p) + ": " + rr.status.message);
  dropUnusedPoints(rr.mesh, bp.size());
  spatialOrder(rr.mesh, bp.size());
  const auto& pmsh = rr.mesh;
  const Clock::time_point lifting = Clock::now();
  out.refineSeconds += secondsBetween(start, lifting);
  const size_t nv = pmsh.vertexCount();
  out.interiorPositions.assign(nv, Vec3{});
  out.layoutFaces.assign(nv, -1);
  out.liftFaces.assign(nv, kNone);
  out.splits.clear();
  int lastFace = -1;
  for (size_t v = bp.size(); v < nv; ++v) {
    // every segment is a chord of the loop or of an inner curve (the required points are free),
    // so a Steiner vertex on a segment is a curve split (patchPslg's segment order): a curve
    // sample made at the patch's turn (finishMeshing)
    if (const int32_t sg = pmsh.vertexSegment[v]; sg >= 0) {
      out.splits.push_back({uint32_t(v), uint32_t(sg), pmsh.vertexParam[v]});
      continue;
    }
    // the walk starts from the previous vertex's face (consecutive refinement vertices are
    // mostly near each other); a hinted locate finds the same point as the grid search
    PullbackPoint q;
    if (!liftPoint(w, pmsh.points[2 * v], pmsh.points[2 * v + 1], q, lastFace))
      fail(Code::NumericalFailure, Stage::Lift, "a refinement vertex lies outside the flattened patch");
    lastFace = q.layoutFace;
    out.interiorPositions[v] = {q.position[0], q.position[1], q.position[2]};
    out.layoutFaces[v] = q.layoutFace;
    out.liftFaces[v] = w.pm.faceInput[q.face];
  }
  out.triangles = pmsh.triangles;
  out.planarPoints = pmsh.points;
  out.liftSeconds += secondsBetween(lifting, Clock::now());
  return true;
}

// A meshing of patch p begins: stamped, so that samples added from now on make it dirty.
void startMeshing(Meshing& m, uint32_t p) {
  PatchWork& w = *m.patches[p];
  w.builtAt = ++m.samples.stamp;
  w.dirty = false;
  w.needsMesh = false;
  w.optimized = false;
}

// The meshing r made from boundary points r.bp becomes patch p's latest: its boundary splits
// become curve samples (in vertex order) and the patches on their curves dirty; its seconds go
// to `busy`.
void finishMeshing(const Surface& surf, Meshing& m, uint32_t p, PatchMeshing& r, StageSeconds& busy) {
  PatchWork& w = *m.patches[p];
  const size_t nv = r.planarPoints.size() / 2;
  w.localToGlobal.assign(nv, kNone);
  for (size_t v = 0; v < r.bp.size(); ++v) w.localToGlobal[v] = r.bp[v].sample;
  for (const PatchMeshing::Split& sp : r.splits)
    w.localToGlobal[sp.vertex] = addSplitSample(surf, m.samples, m.patches, w, r.bp, r.inner, sp.segment, sp.t);
  w.interiorPositions = std::move(r.interiorPositions);
  w.layoutFaces = std::move(r.layoutFaces);
  w.liftFaces = std::move(r.liftFaces);
  w.triangles = std::move(r.triangles);
  w.planarPoints = std::move(r.planarPoints);
  w.optimizeCache = {};
  busy.refine += r.refineSeconds;
  busy.lift += r.liftSeconds;
}

}  // namespace

PatchMeshing refineApart(const Surface& surf, const RemeshOptions& opt, const Meshing& m, uint32_t p, bool splitSegments) {
  PatchMeshing r;
  r.bp = boundaryPoints(surf, m.samples, *m.patches[p], &r.inner);
  if (degenerateBoundary(r.bp)) {
    r.needsRepair = true;
    return r;
  }
  Status crossing;
  r.needsRepair = !refineAndLift(surf, opt, m, p, splitSegments, r.bp, r.inner, r, crossing);
  return r;
}

void commitMeshing(const Surface& surf, Meshing& m, uint32_t p, PatchMeshing& r, StageSeconds& busy) {
  startMeshing(m, p);
  finishMeshing(surf, m, p, r, busy);
}

void meshPatch(const Surface& surf, const RemeshOptions& opt, Meshing& m, uint32_t p, StageSeconds& busy,
               bool splitSegments) {
  PatchWork& w = *m.patches[p];
  startMeshing(m, p);
  PatchMeshing r;
  r.bp = boundaryPoints(surf, m.samples, w, &r.inner);
  std::vector<BoundaryPoint>& bp = r.bp;
  // A small patch bounded by short curves can have fewer than 3 boundary samples, or only
  // collinear ones (two curves between the same two corners): add a sample in the middle of the
  // longest boundary stretch (shared with the neighbour like any segment split) until it has a
  // proper polygon.
  for (int guard = 0; guard < 8 && degenerateBoundary(bp); ++guard) {
    size_t longest = 0;
    double best = -1;
    const size_t loopPoints = loopPointCount(bp);
    for (size_t i = 0; i < loopPoints; ++i) {
      // its length along the flattened boundary
      double len = 0;
      const auto& loop = w.pm.boundaryLoops[0];
      for (const Piece& pc : stretch(w, bp[i], bp[(i + 1) % loopPoints], loopPoints)) {
        const auto& h = loop[pc.k];
        uint32_t va = w.pm.mesh.triangles[3 * h.face + h.corner], vb = w.pm.mesh.triangles[3 * h.face + (h.corner + 1) % 3];
        len += (pc.t1 - pc.t0) * dmath::hypot(w.flat.uv[2 * vb] - w.flat.uv[2 * va], w.flat.uv[2 * vb + 1] - w.flat.uv[2 * va + 1]);
      }
      if (len > best) best = len, longest = i;
    }
    addSplitSample(surf, m.samples, m.patches, w, bp, r.inner, uint32_t(longest), 0.5);
    w.builtAt = ++m.samples.stamp;
    w.dirty = false;
    bp = boundaryPoints(surf, m.samples, w, &r.inner);
  }
  if (degenerateBoundary(bp)) fail(Code::InternalError, Stage::Refine, "patch " + std::to_string(p) + ": its boundary samples do not make a polygon");
  for (int attempt = 0;; ++attempt) {
    Status rejected;
    if (refineAndLift(surf, opt, m, p, splitSegments, bp, r.inner, r, rejected)) break;
    if (attempt >= kCrossingRepairs) fail(rejected.code, rejected.stage, rejected.message);
    // The chords between boundary samples cross where the boundary doubles back within a sample
    // spacing: split the crossing chords (shared with the neighbours like any segment split)
    // and try again.
    const std::vector<uint32_t> crossing = crossingSegments(patchPslg(bp, r.inner));
    if (crossing.empty()) fail(Code::InternalError, Stage::Refine, "patch " + std::to_string(p) + ": invalid boundary, but no chords cross");
    for (uint32_t sg : crossing) addSplitSample(surf, m.samples, m.patches, w, bp, r.inner, sg, 0.5);
    w.builtAt = ++m.samples.stamp;
    w.dirty = false;
    bp = boundaryPoints(surf, m.samples, w, &r.inner);
  }
  finishMeshing(surf, m, p, r, busy);
}

// The free vertices the optimization's collapses left without triangles go; the others are
// renumbered in order (the curve samples keep their places in localToGlobal).
static void dropUnusedVertices(PatchWork& w) {
  const size_t nv = w.planarPoints.size() / 2;
  std::vector<uint8_t> used(nv, 0);
  for (const uint32_t v : w.triangles) used[v] = 1;
  std::vector<uint32_t> to(nv, kNone);
  size_t n = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (!used[v] && w.localToGlobal[v] == kNone) continue;
    to[v] = uint32_t(n);
    w.planarPoints[2 * n] = w.planarPoints[2 * v];
    w.planarPoints[2 * n + 1] = w.planarPoints[2 * v + 1];
    w.localToGlobal[n] = w.localToGlobal[v];
    w.interiorPositions[n] = w.interiorPositions[v];
    w.layoutFaces[n] = w.layoutFaces[v];
    w.liftFaces[n] = w.liftFaces[v];
    ++n;
  }
  if (n == nv) return;
  w.planarPoints.resize(2 * n);
  w.localToGlobal.resize(n);
  w.interiorPositions.resize(n);
  w.layoutFaces.resize(n);
  w.liftFaces.resize(n);
  for (uint32_t& v : w.triangles) v = to[v];
  w.optimizeCache = {};
}

OptimizeResult optimizeMesh(const Surface& surf, const RemeshOptions& opt, const CurveSamples& samples, PatchWork& w,
                            const std::vector<uint8_t>& active) {
  OptimizeResult res;
  w.optimized = true;
  if (!opt.optimize || opt.optimizeIterations == 0) return res;
  const size_t nv = w.planarPoints.size() / 2;
  std::vector<Vec3> pos(nv);
  std::vector<uint8_t> fixed(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    fixed[v] = w.localToGlobal[v] != kNone;
    pos[v] = fixed[v] ? samples.cm.samples[w.localToGlobal[v]].position : w.interiorPositions[v];
  }
  optimization::OptimizeOptions oo;
  oo.minAngleDeg = opt.minAngle;
  oo.maxIterations = opt.optimizeIterations;
  oo.tolerance = opt.optimizeTolerance;
  // the inner curves' segments: consecutive samples of each (all in this patch)
  if (!w.inner.empty()) {
    std::unordered_map<uint32_t, uint32_t> localOf;
    for (uint32_t v = 0; v < nv; ++v)
      if (fixed[v]) localOf.emplace(w.localToGlobal[v], v);
    for (const InnerCurve& ic : w.inner) {
      const auto& ids = samples.cm.curveSamples[ic.curve];
      for (size_t i = 0; i + 1 < ids.size(); ++i) {
        const auto a = localOf.find(ids[i]), b = localOf.find(ids[i + 1]);
        if (a == localOf.end() || b == localOf.end())
          fail(Code::InternalError, Stage::Optimize, "an inner curve's sample is not in its patch's meshing");
        oo.keptEdges.push_back(optimization::keptEdgeKey(a->second, b->second));
      }
    }
    std::sort(oo.keptEdges.begin(), oo.keptEdges.end());
  }
  // the planar refinement left the interior triangles below the bound and its margin: passes
  // aimed at those still below the bound in 3D, the valence operations, kExtraPassesAbove more
  // passes (the moves even out the stars the flips and collapses change) and the gradient steps
  // for the stars within kSearchAboveBoundDeg of the bound
  if (aboveMaxPlanar(opt.minAngle)) {
    oo.boundPasses = kBoundPasses;
    oo.valenceOperations = true;
    oo.maxIterations += kExtraPassesAbove;
    oo.searchBelowDeg = opt.minAngle + kSearchAboveBoundDeg;
  }
  // per vertex: the layout face its latest lift landed in, where the next one starts looking
  auto lift = [&](uint32_t v, double x, double y, Vec3& out) {
    if (v >= w.layoutFaces.size()) {  // a vertex splitBelowBound adds
      w.layoutFaces.resize(v + 1, -1);
      w.liftFaces.resize(v + 1, kNone);
    }
    PullbackPoint q;
    if (!liftPoint(w, x, y, q, w.layoutFaces[v])) return false;
    w.layoutFaces[v] = q.layoutFace;
    w.liftFaces[v] = w.pm.faceInput[q.face];  // of the latest candidate: a hint, near the kept one
    out = {q.position[0], q.position[1], q.position[2]};
    return true;
  };
  // the patch's input vertices guard every optimization (optimize.h): no move or flip takes the
  // output farther from them than the chord tolerance, or farther than it was: unguarded, the
  // first one raised the Hausdorff distance for no gain in angles (docs/decisions/0011)
  optimization::SurfaceSamples guard;
  const double tolerance = surf.chordTolerance;
  // a patch within tolerance/2 of a plane needs no guard: the input patch and every output
  // triangle over it (vertices on the input) lie in that slab and share the boundary curves, so
  // no moving can take the output farther than the tolerance from the input there (a CAD model's
  // flat faces), and the guard's bucketing is saved
  if (w.slabHalfWidth < 0) w.slabHalfWidth = slabHalfWidth(w.pm);
  if (!(w.slabHalfWidth <= 0.5 * tolerance)) {
    guard.xy = w.flat.uv;
    guard.pos.resize(w.pm.vertexInput.size());
    for (size_t v = 0; v < guard.pos.size(); ++v) guard.pos[v] = surf.g.positions[w.pm.vertexInput[v]];
    guard.tolerance = tolerance;
  }
  // between two optimizations of one meshing only slides move vertices, and `active` has every
  // vertex of a slid sample's stars
  optimization::OptimizeStats st = optimization::optimizePatch(w.planarPoints, w.triangles, pos, fixed, lift, oo, active, guard, &w.optimizeCache);
  // what the moves and flips could not lift to the bound, a new vertex may
  const optimization::SplitStats sp = optimization::splitBelowBound(w.planarPoints, w.triangles, pos, fixed, lift, oo, guard);
  const size_t nvNow = w.planarPoints.size() / 2;
  w.localToGlobal.resize(nvNow, kNone);
  w.interiorPositions.resize(nvNow);
  w.layoutFaces.resize(nvNow, -1);
  w.liftFaces.resize(nvNow, kNone);
  if (sp.splits > 0) w.optimizeCache = {};
  for (size_t v = 0; v < nvNow; ++v)
    if (!fixed[v]) w.interiorPositions[v] = pos[v];
  dropUnusedVertices(w);
  res.moves = st.moves + sp.optimize.moves;
  res.flips = st.flips + sp.optimize.flips;
  res.splits = sp.splits;
  res.collapses = st.collapses + sp.optimize.collapses;
  res.splitsCapped = sp.capped;
  return res;
}

}  // namespace conformesh::pipeline
