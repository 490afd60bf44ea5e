#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "conformesh.h"
#include "planar/predicates.h"
#include "test_meshes.h"
#include "features/test_shapes.h"

#include <fstream>
#include <iterator>

using namespace conformesh;

namespace {

// Distance from point q to triangle f of M (exact closest point, Ericson's regions).
double pointTriangleDistance(const MeshBuffers& M, uint32_t f, const double* q) {
  const double* a = &M.positions[3 * size_t(M.triangles[3 * f])];
  const double* b = &M.positions[3 * size_t(M.triangles[3 * f + 1])];
  const double* c = &M.positions[3 * size_t(M.triangles[3 * f + 2])];
  auto sub = [](const double* x, const double* y, double* r) { for (int k = 0; k < 3; ++k) r[k] = x[k] - y[k]; };
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  double ab[3], ac[3], ap[3], bp[3], cp[3], r[3];
  sub(b, a, ab); sub(c, a, ac); sub(q, a, ap);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  double best[3];
  auto set = [&](double s, double t) { for (int k = 0; k < 3; ++k) best[k] = a[k] + s * ab[k] + t * ac[k]; };
  sub(q, b, bp); sub(q, c, cp);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  if (d1 <= 0 && d2 <= 0) set(0, 0);
  else if (d3 >= 0 && d4 <= d3) set(1, 0);
  else if (d6 >= 0 && d5 <= d6) set(0, 1);
  else if (vc <= 0 && d1 >= 0 && d3 <= 0) set(d1 / (d1 - d3), 0);
  else if (vb <= 0 && d2 >= 0 && d6 <= 0) set(0, d2 / (d2 - d6));
  else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    set(1 - w, w);
  } else {
    const double den = 1 / (va + vb + vc);
    set(vb * den, vc * den);
  }
  sub(q, best, r);
  return std::sqrt(dot(r, r));
}

double bboxDiag(const MeshBuffers& M) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t v = 0; v < M.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], M.positions[3 * v + k]);
      hi[k] = std::max(hi[k], M.positions[3 * v + k]);
    }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

}  // namespace

MeshBuffers readData(const std::string& name) {
  std::ifstream in(std::string(CONFORMESH_DATA_DIR) + "/" + name, std::ios::binary);
  REQUIRE(in.good());
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ReadOptions ro;
  ro.fileName = name;
  return readMesh(bytes, ro).mesh;
}

// Random planar points inside the layout: pull back, check margin, distance to the input
// triangle, and continuity (nearby planar points land near each other on the surface).
void checkPullback(const MeshBuffers& M, const FlatPatch& P, int samples, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  const double diag = bboxDiag(M);
  const auto& L = P.layout;
  int located = 0;
  double worstDist = 0, worstMargin = 0;
  for (int s = 0; s < samples; ++s) {
    // A random point in a random layout triangle.
    const size_t t = size_t(U(rng) * L.triangleCount()) % L.triangleCount();
    double a = U(rng), b = U(rng);
    if (a + b > 1) { a = 1 - a; b = 1 - b; }
    const double* p0 = &L.positions[3 * size_t(L.triangles[3 * t])];
    const double* p1 = &L.positions[3 * size_t(L.triangles[3 * t + 1])];
    const double* p2 = &L.positions[3 * size_t(L.triangles[3 * t + 2])];
    const double x = p0[0] + a * (p1[0] - p0[0]) + b * (p2[0] - p0[0]);
    const double y = p0[1] + a * (p1[1] - p0[1]) + b * (p2[1] - p0[1]);
    PullbackPoint q;
    if (!P.pullback.locate(x, y, q)) continue;
    ++located;
    worstDist = std::max(worstDist, pointTriangleDistance(M, q.face, q.position));
    worstMargin = std::min(worstMargin, q.margin);
  }
  CHECK(located == samples);
  CHECK(worstDist <= 1e-9 * diag);
  CHECK(worstMargin >= -1e-9);
}

// Free boundary: converged, a valid layout, and 10,000 pulled-back points on the input surface.
FlatPatch flattenFreeValid(const MeshBuffers& M, unsigned seed) {
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  FlatPatch P = flatten(M, o);
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  CHECK(P.report.boundaryCrossings == 0);
  checkPullback(M, P, 10000, seed);
  return P;
}

TEST_CASE("flatten: planar disk with slivers stays similar to itself (flips + exact pull-back)") {
  // Free boundary (u = 0 on the boundary): the input is the unique solution, reached through a
  // non-Delaunay input (Ptolemy flips change the metric, Newton must bring it back).
  MeshBuffers M = testmesh::polarDisk(8, 24, 0.12);
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  FlatPatch P = flatten(M, o);
  CHECK(P.report.euclideanFlips > 0);
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  // uv is a similarity image of the input: compare all pairwise distance ratios to vertex 0,1.
  const double s = std::hypot(P.uv[2] - P.uv[0], P.uv[3] - P.uv[1]) /
                   std::hypot(M.positions[3] - M.positions[0], M.positions[4] - M.positions[1]);
  double worst = 0;
  for (size_t v = 0; v < M.vertexCount(); ++v)
    for (size_t w : {size_t(0), size_t(7), size_t(100)}) {
      const double d2 = std::hypot(P.uv[2 * v] - P.uv[2 * w], P.uv[2 * v + 1] - P.uv[2 * w + 1]);
      const double d3 = std::hypot(M.positions[3 * v] - M.positions[3 * w], M.positions[3 * v + 1] - M.positions[3 * w + 1]);
      worst = std::max(worst, std::fabs(d2 - s * d3));
    }
  CHECK(worst < 1e-9);
  CHECK(P.report.angleDistortionMax < 1 + 1e-8);
  // The pull-back of a planar point is the similarity's inverse image.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-0.6, 0.6);
  // Similarity from vertex 0 (centre) and vertex 1.
  const double ux = (P.uv[2] - P.uv[0]) / s, uy = (P.uv[3] - P.uv[1]) / s;
  const double mx = M.positions[3], my = M.positions[4];
  const double c0 = (ux * mx + uy * my) / (mx * mx + my * my), s0 = (uy * mx - ux * my) / (mx * mx + my * my);
  double worstP = 0;
  for (int k = 0; k < 500; ++k) {
    const double X = U(rng), Y = U(rng);  // 3D point in the disk
    const double x = P.uv[0] + s * (c0 * X - s0 * Y), y = P.uv[1] + s * (s0 * X + c0 * Y);
    PullbackPoint q;
    REQUIRE(P.pullback.locate(x, y, q));
    worstP = std::max(worstP, std::hypot(q.position[0] - X, q.position[1] - Y));
  }
  CHECK(worstP < 1e-9);
  checkPullback(M, P, 2000, 1);
}

TEST_CASE("flatten: spherical cap, free boundary; quadratic convergence; pull-back on the surface") {
  MeshBuffers M = testmesh::sphericalCap(10, 40, 1.3);
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  FlatPatch P = flatten(M, o);
  std::printf("cap/free residuals:");
  for (double r : P.report.residuals) std::printf(" %.3e", r);
  std::printf("\n");
  const auto& r = P.report.residuals;
  REQUIRE(r.size() >= 3);
  CHECK(r.back() <= 1e-9);
  // Quadratic: r_{k+1} <= C r_k^2 in the last steps where r_k < 1e-2.
  for (size_t k = 0; k + 1 < r.size(); ++k)
    if (r[k] < 1e-2 && r[k + 1] > 1e-13) CHECK(r[k + 1] <= 10.0 * r[k] * r[k]);
  CHECK(P.report.gaussBonnetError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  checkPullback(M, P, 2000, 2);
}

TEST_CASE("flatten: annulus maps to a circle domain without overlap") {
  MeshBuffers M = testmesh::annulus(6, 48, 0.35, 0.4);
  FlatPatch P = flatten(M);
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  CHECK(P.report.boundaryCrossings == 0);
  CHECK(P.report.layoutLengthError < 1e-8);
  REQUIRE(P.boundaryLoops.size() == 2);
  // Both loops are circles.
  for (const auto& loop : P.boundaryLoops) {
    double cx = 0, cy = 0;
    for (uint32_t v : loop) { cx += P.uv[2 * v]; cy += P.uv[2 * v + 1]; }
    cx /= loop.size(); cy /= loop.size();
    double rmin = 1e300, rmax = 0;
    for (uint32_t v : loop) {
      const double rr = std::hypot(P.uv[2 * v] - cx, P.uv[2 * v + 1] - cy);
      rmin = std::min(rmin, rr); rmax = std::max(rmax, rr);
    }
    CHECK((rmax - rmin) / rmax < 1e-6);
  }
  checkPullback(M, P, 2000, 3);
}

TEST_CASE("flatten data: holes.off (7 loops) -> circle domain; mech-holes-shark (4 loops) free outer loop") {
  {
    MeshBuffers M = readData("holes.off");
    FlatPatch P = flatten(M);
    CHECK(P.report.maxCurvatureError <= 1e-9);
    CHECK(P.report.gaussBonnetError <= 1e-9);
    CHECK(P.report.invertedTriangles == 0);
    CHECK(P.report.boundaryCrossings == 0);
    CHECK(P.boundaryLoops.size() == 7);
    checkPullback(M, P, 10000, 11);
  }
  {
    flattenFreeValid(readData("mech-holes-shark.off"), 12);
  }
}

TEST_CASE("flatten data: camelhead needles (min angle 0.55 deg) converge with flips, fail without") {
  MeshBuffers M = readData("camelhead.off");
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  FlatPatch P = flatten(M, o);
  std::printf("camelhead with flips: %d iterations, %lld Ptolemy + %lld Euclidean flips, residuals:", P.report.iterations,
              P.report.flips, P.report.euclideanFlips);
  for (double r : P.report.residuals) std::printf(" %.2e", r);
  std::printf("\n");
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.flips + P.report.euclideanFlips > 0);
  CHECK(P.report.invertedTriangles == 0);
  checkPullback(M, P, 10000, 13);
  o.flips = false;
  try {
    flatten(M, o);
    FAIL("the flow without flips was expected to break the triangle inequality on camelhead");
  } catch (const Error& e) {
    std::printf("camelhead without flips: %s: %s\n", codeName(e.code()), e.what());
    CHECK((e.code() == Code::NotConverged || e.code() == Code::IterationLimit));
  }
}

TEST_CASE("flatten: a ramp of one and a half turns lays out overlapping itself; the report names the crossing edges") {
  const MeshBuffers M = testshapes::helicoidStrip(1.5, 1.0, 2.0, 0.2, 72, 6);
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  o.pullback = false;
  CHECK_THROWS_AS(flatten(M, o), Error);
  o.requireValidLayout = false;
  const FlatPatch f = flatten(M, o);
  CHECK(f.report.boundaryCrossings > 0);
  CHECK(!f.report.invalidLayout.empty());
  REQUIRE(f.report.boundaryCrossingEdges.size() == size_t(f.report.boundaryCrossings));
  for (const auto& c : f.report.boundaryCrossingEdges) {
    const double* a0 = &f.uv[2 * c[0]];
    const double* a1 = &f.uv[2 * c[1]];
    const double* b0 = &f.uv[2 * c[2]];
    const double* b1 = &f.uv[2 * c[3]];
    // the two edges cross: each one's ends lie on either side of the other's line
    CHECK(planar::orient2d(a0, a1, b0) * planar::orient2d(a0, a1, b1) <= 0);
    CHECK(planar::orient2d(b0, b1, a0) * planar::orient2d(b0, b1, a1) <= 0);
  }
  // under one turn the same ramp lays out
  const FlatPatch g = flatten(testshapes::helicoidStrip(0.75, 1.0, 2.0, 0.2, 36, 6), o);
  CHECK(g.report.boundaryCrossings == 0);
  CHECK(g.report.invalidLayout.empty());
  // a narrow ramp of 1.1 turns: every triangle in place and every length kept, the border over
  // itself; the message says so (not precision, which no split of the patch would be about)
  const FlatPatch h = flatten(testshapes::helicoidStrip(1.1, 1.0, 2.0, 0.2, 52, 3), o);
  REQUIRE(h.report.boundaryCrossings > 0);
  CHECK(h.report.invertedTriangles == 0);
  CHECK(h.report.layoutLengthError <= 1e-3);
  CHECK(h.report.invalidLayout.find("border overlaps itself") != std::string::npos);
  CHECK(h.report.invalidLayout.find("double precision") == std::string::npos);
}

TEST_CASE("flatten: corner-preserving boundary makes a square of a bent square patch") {
  // A bent 8x8 grid: corners get 90 degrees, the rest of the boundary straight.
  MeshBuffers M = testmesh::needleGrid(1.0, 8, 8, 0.4);
  FlattenOptions o;
  o.boundary = BoundaryCondition::Corners;
  for (uint32_t v : {0u, 8u, 80u, 72u}) o.corners.emplace_back(v, M_PI / 2);
  FlatPatch P = flatten(M, o);
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  // Boundary vertices between two corners are collinear.
  auto collinear = [&](uint32_t a, uint32_t b, uint32_t c) {
    const double* A = &P.uv[2 * a]; const double* B = &P.uv[2 * b]; const double* C = &P.uv[2 * c];
    const double cr = (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
    return std::fabs(cr) / (std::hypot(B[0] - A[0], B[1] - A[1]) * std::hypot(C[0] - A[0], C[1] - A[1]));
  };
  for (uint32_t i = 1; i < 8; ++i) CHECK(collinear(0, 8, i) < 1e-8);
  for (uint32_t j = 1; j < 8; ++j) CHECK(collinear(0, 72, 9 * j) < 1e-8);
  checkPullback(M, P, 2000, 14);
}

TEST_CASE("flatten: bad input gets a clear status") {
  MeshBuffers M = testmesh::polarDisk(3, 8);
  auto code = [](const MeshBuffers& m) {
    try { flatten(m); } catch (const Error& e) { return e.code(); }
    return Code::Ok;
  };
  MeshBuffers a = M;
  a.triangles[4] = 999;
  CHECK(code(a) == Code::IndexOutOfRange);
  MeshBuffers b = M;
  b.positions[5] = std::nan("");
  CHECK(code(b) == Code::NonFiniteCoordinate);
  MeshBuffers c = M;
  std::swap(c.triangles[0], c.triangles[1]);
  CHECK(code(c) == Code::InconsistentOrientation);
  CHECK(code(MeshBuffers{}) == Code::EmptyMesh);
  // A closed octahedron: no boundary.
  MeshBuffers d;
  d.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  d.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  CHECK(code(d) == Code::InvalidTopology);
  FlattenOptions o;
  o.maxIterations = 1;
  try { flatten(testmesh::sphericalCap(6, 20, 1.5), o); FAIL("expected IterationLimit"); }
  catch (const Error& e) { CHECK(e.code() == Code::IterationLimit); }
}

TEST_CASE("flatten: kept edges stay straight in the layout, the pull-back projective along them") {
  // a twisted cap: skinny triangles whose edges the intrinsic Delaunay flips replace, and a
  // scale factor u that varies along every spoke
  const int rings = 10, m = 40;
  const MeshBuffers M = testmesh::sphericalCap(rings, m, 1.3, 0.35);
  const auto id = [&](int k, int j) { return uint32_t(1 + (k - 1) * m + (j % m)); };
  std::vector<std::array<uint32_t, 2>> spoke;  // (k, j) -> (k + 1, j): an edge of the mesh
  for (int j = 0; j < m; j += 5)
    for (int k = 1; k < rings; ++k) spoke.push_back({id(k, j), id(k + 1, j)});
  // the worst distance, over the spoke edges, from the pull-back of points of each planar edge
  // to the point edgeSurfaceParam gives on the input edge, relative to the edge's length; and
  // the same to the affine point
  const auto offEdge = [&](const FlatPatch& P, double& affine) {
    double worst = 0;
    affine = 0;
    for (const auto& [a, b] : spoke) {
      const double* A = &M.positions[3 * size_t(a)];
      const double* B = &M.positions[3 * size_t(b)];
      const double len = std::sqrt((B[0] - A[0]) * (B[0] - A[0]) + (B[1] - A[1]) * (B[1] - A[1]) + (B[2] - A[2]) * (B[2] - A[2]));
      for (double t = 0.1; t < 0.95; t += 0.2) {
        PullbackPoint q;
        REQUIRE(P.pullback.locate(P.uv[2 * a] + t * (P.uv[2 * b] - P.uv[2 * a]), P.uv[2 * a + 1] + t * (P.uv[2 * b + 1] - P.uv[2 * a + 1]), q));
        const double s = edgeSurfaceParam(P.u, a, b, t);
        double d = 0, da = 0;
        for (int k = 0; k < 3; ++k) {
          d += (q.position[k] - (A[k] + s * (B[k] - A[k]))) * (q.position[k] - (A[k] + s * (B[k] - A[k])));
          da += (q.position[k] - (A[k] + t * (B[k] - A[k]))) * (q.position[k] - (A[k] + t * (B[k] - A[k])));
        }
        worst = std::max(worst, std::sqrt(d) / len);
        affine = std::max(affine, std::sqrt(da) / len);
        CHECK(edgePlanarParam(P.u, a, b, s) == doctest::Approx(t).epsilon(1e-12));
      }
    }
    return worst;
  };
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  double affine = 0;
  const double unkept = offEdge(flatten(M, o), affine);
  o.keepEdges = spoke;
  const FlatPatch P = flatten(M, o);
  CHECK(P.report.invertedTriangles == 0);
  const double kept = offEdge(P, affine);
  std::printf("kept edges: off the edge %.2e kept, %.2e not kept; affine placement %.2e\n", kept, unkept, affine);
  CHECK(kept <= 1e-9);
  CHECK(unkept > 1e-3);  // flipped away: the planar chord is not the edge's image
  CHECK(affine > 1e-3);  // u varies along the spokes: the affine point is not the pull-back's
  // an edge to keep must be an interior edge of the mesh
  o.keepEdges = {{id(rings, 0), id(rings, 1)}};
  try { flatten(M, o); FAIL("expected InvalidArgument"); }
  catch (const Error& e) { CHECK(e.code() == Code::InvalidArgument); }
  o.keepEdges = {{0, id(rings, 0)}};
  try { flatten(M, o); FAIL("expected InvalidArgument"); }
  catch (const Error& e) { CHECK(e.code() == Code::InvalidArgument); }
}

namespace {
// Interior angle of the laid-out outer loop at its i-th vertex (domain on the left).
double layoutAngle(const FlatPatch& P, size_t i) {
  const auto& loop = P.boundaryLoops[0];
  const size_t n = loop.size();
  const double* v = &P.uv[2 * size_t(loop[i])];
  const double* a = &P.uv[2 * size_t(loop[(i + 1) % n])];
  const double* b = &P.uv[2 * size_t(loop[(i + n - 1) % n])];
  const double ax = a[0] - v[0], ay = a[1] - v[1], bx = b[0] - v[0], by = b[1] - v[1];
  const double t = std::atan2(ax * by - ay * bx, ax * bx + ay * by);
  return t < 0 ? t + 2 * M_PI : t;
}
}  // namespace

TEST_CASE("flatten: jagged boundary, every zigzag vertex a corner: angles scaled to close the polygon") {
  // On a curved patch the 3D angles of a staircase boundary do not sum to (n - 2) pi
  // (Gauss–Bonnet): the targets are infeasible as given, and used to leave the whole defect at
  // the pinned vertex. They are scaled to close; the layout has exactly the scaled angles.
  MeshBuffers M = testmesh::staircase(12, 5, 1.5);
  FlattenOptions o;
  o.boundary = BoundaryCondition::Corners;
  o.corners = detectCorners(M, 1e-3);
  FlatPatch P = flatten(M, o);
  REQUIRE(P.boundaryLoops.size() == 1);
  CHECK(o.corners.size() == P.boundaryLoops[0].size());  // every outer vertex is a corner
  CHECK(std::fabs(P.report.cornerAngleScale - 1) > 1e-3);
  CHECK(P.report.maxCurvatureError <= 1e-9);
  CHECK(P.report.gaussBonnetError <= 1e-9);
  CHECK(P.report.invertedTriangles == 0);
  double worst = 0;
  const auto& loop = P.boundaryLoops[0];
  for (size_t i = 0; i < loop.size(); ++i)
    for (const auto& c : o.corners)
      if (c.first == loop[i]) worst = std::max(worst, std::fabs(layoutAngle(P, i) - P.report.cornerAngleScale * c.second));
  CHECK(worst < 1e-8);
  checkPullback(M, P, 2000, 15);
}

TEST_CASE("flatten: jagged boundary with smooth stretches converges quadratically (fixed targets)") {
  // 10 degrees: the staircase steps are corners, the straight grid sides are smooth and take the
  // Gauss–Bonnet rest by input arc length. Targets spread by the current flat lengths moved
  // with u and the frozen-target Newton iteration went up and down for 27 iterations here.
  for (double c : {1.5, 3.0, 6.0}) {
    MeshBuffers M = testmesh::staircase(12, 5, c);
    FlattenOptions o;
    o.boundary = BoundaryCondition::Corners;
    o.corners = detectCorners(M, 10 * M_PI / 180);
    REQUIRE(o.corners.size() > 4);
    FlatPatch P = flatten(M, o);
    const auto& r = P.report.residuals;
    CHECK(r.back() <= 1e-9);
    CHECK(P.report.invertedTriangles == 0);
    for (size_t k = 0; k + 1 < r.size(); ++k)
      if (r[k] < 1e-2 && r[k + 1] > 1e-13) CHECK(r[k + 1] <= 10.0 * r[k] * r[k]);
    // Every corner keeps its 3D angle (the smooth vertices absorbed the Gauss–Bonnet rest).
    CHECK(P.report.cornerAngleScale == 1.0);
    const auto& loop = P.boundaryLoops[0];
    double worst = 0;
    for (size_t i = 0; i < loop.size(); ++i)
      for (const auto& cr : o.corners)
        if (cr.first == loop[i]) worst = std::max(worst, std::fabs(layoutAngle(P, i) - cr.second));
    CHECK(worst < 1e-8);
  }
}

TEST_CASE("flatten data: alligator circle needs more range than doubles hold; free boundary lays out") {
  // The round disk crowds the alligator's legs and tail exponentially (Schwarz–Christoffel
  // crowding): e^{2u} spans ~1e47, edges ~1e-24 of the domain. No double-precision layout can
  // hold that: a NumericalFailure that says so, with the numbers.
  MeshBuffers M = readData("alligator.obj");
  try {
    flatten(M);
    FAIL("the circle map of alligator.obj was expected to exceed double precision");
  } catch (const Error& e) {
    std::printf("alligator circle: %s: %s\n", codeName(e.code()), e.what());
    CHECK(e.code() == Code::NumericalFailure);
    CHECK(std::string(e.what()).find("e^{2u} spanning") != std::string::npos);
  }
  const FlatPatch P = flattenFreeValid(M, 16);
  CHECK(P.report.areaDistortionRange < 1e6);
}

TEST_CASE("flatten data: inputTrianglesInvertedInUv counts the inverted uv triangles of the OBJ written with the uv") {
  // bunny's free map leaves a few input triangles inverted in vertex uv (the layout has none):
  // the count must be that of the file, read back, with the exact orientation of its uv
  MeshBuffers M = readData("stanford-bunny.obj");
  FlattenOptions o;
  o.boundary = BoundaryCondition::Free;
  o.pullback = false;
  const FlatPatch P = flatten(M, o);
  CHECK(P.report.invertedTriangles == 0);
  M.uvs = P.uv;
  ReadOptions ro;
  ro.fileName = "written.obj";
  const MeshBuffers W = readMesh(writeMesh(M, MeshFormat::Obj), ro).mesh;
  REQUIRE(W.uvs.size() == 2 * W.vertexCount());
  REQUIRE(W.triangleCount() == M.triangleCount());
  int inverted = 0;
  for (size_t f = 0; f < W.triangleCount(); ++f) {
    const uint32_t* t = &W.triangles[3 * f];
    inverted += !(planar::orient2d(&W.uvs[2 * t[0]], &W.uvs[2 * t[1]], &W.uvs[2 * t[2]]) > 0);
  }
  MESSAGE("stanford-bunny free: " << inverted << " input triangles inverted in uv");
  CHECK(inverted == P.report.inputTrianglesInvertedInUv);
}
