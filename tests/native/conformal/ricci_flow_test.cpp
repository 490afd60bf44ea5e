#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "conformal/intrinsic_triangulation.h"
#include "conformal/layout.h"
#include "conformal/ricci_flow.h"
#include "conformal/triangle_geometry.h"
#include "test_meshes.h"

using namespace conformesh;
using namespace conformesh::conformal;

TEST_CASE("kahan angles: needles keep their digits, sums are pi") {
  bool valid = true;
  const double eps = 1e-10;
  // Isosceles needle: apex angle ~ eps.
  const double apex = kahanAngle(eps, 1.0, 1.0, valid);
  CHECK(valid);
  CHECK(std::fabs(apex - eps) <= 1e-20);
  double lam[3] = {std::log(1.0), std::log(1.0), std::log(eps * eps)};
  double ang[3];
  CHECK(anglesFromLogLengths(lam, ang));
  CHECK(std::fabs(ang[0] + ang[1] + ang[2] - kPi) < 1e-15);
  double bad[3] = {std::log(9.0), std::log(1.0), std::log(1.0)};  // 3 > 1 + 1
  CHECK_FALSE(anglesFromLogLengths(bad, ang));
}

TEST_CASE("flips: Ptolemy flip keeps the horocycle periods and Delaunay pass terminates") {
  MeshBuffers M = testmesh::polarDisk(6, 16, 0.15);
  IntrinsicTriangulation T = buildIntrinsicTriangulation(M);
  std::vector<double> u(T.nV, 0.0), angle0;
  CHECK(computeAngles(T, u, angle0) == 0);
  auto K0 = vertexCurvature(T, angle0);
  for (int v = 0; v < T.nV; ++v)
    if (!T.boundaryVertex[v]) REQUIRE(std::fabs(K0[v]) < 1e-12);
  CHECK_FALSE(isDelaunay(T, u));
  const long long n = flipToDelaunay(T, u, 1000000);
  CHECK(n > 0);
  CHECK(isDelaunay(T, u));
  // Ptolemy flips change the Euclidean metric but keep the decorated hyperbolic surface: the
  // horocycle around every interior vertex keeps its length, and positions stay consistent.
  std::vector<double> horo(T.nV, 0.0);
  for (int h = 0; h < 3 * T.nF; ++h) {
    const int p = IntrinsicTriangulation::prev(h), n = IntrinsicTriangulation::next(h);
    horo[T.vert[h]] += std::exp(0.5 * (T.lambda[T.edge[n]] - T.lambda[T.edge[h]] - T.lambda[T.edge[p]]));
  }
  for (int v = 0; v < T.nV; ++v) CHECK(std::fabs(horo[v] - T.horoTotal[v]) <= 1e-12 * T.horoTotal[v]);
  // Flipping an edge twice restores its length.
  for (int e = 0; e < T.nE; ++e)
    if (T.canFlip(e)) {
      const double before = T.lambda[e];
      T.flip(e);
      T.flip(e);
      CHECK(std::fabs(T.lambda[e] - before) < 1e-12);
    }
}

TEST_CASE("Hessian is the cotangent Laplacian: finite differences of K") {
  MeshBuffers M = testmesh::sphericalCap(4, 10, 1.0);
  IntrinsicTriangulation T = buildIntrinsicTriangulation(M);
  std::vector<double> u(T.nV, 0.0), angle;
  for (int v = 0; v < T.nV; ++v) u[v] = 0.1 * std::sin(3.0 * v);
  computeAngles(T, u, angle);
  const int i = 5;
  const double h = 1e-6;
  std::vector<double> up = u, um = u, ap, am;
  up[i] += h;
  um[i] -= h;
  computeAngles(T, up, ap);
  computeAngles(T, um, am);
  auto Kp = vertexCurvature(T, ap), Km = vertexCurvature(T, am);
  // Expected column i of L: L_ii = sum w, L_ij = -w, w = 1/2 cot opposite.
  std::vector<double> col(T.nV, 0.0);
  for (int hh = 0; hh < 3 * T.nF; ++hh) {
    const int a = T.vert[hh], b = T.tip(hh);
    const double w = 0.5 * cotOfAngle(angle[hh]);
    if (a == i) { col[i] += w; col[b] -= w; }
    if (b == i) { col[i] += w; col[a] -= w; }
  }
  for (int v = 0; v < T.nV; ++v) CHECK(std::fabs((Kp[v] - Km[v]) / (2 * h) - col[v]) < 1e-6);
}

TEST_CASE("flow: planar regular disk is already a solution; spherical cap becomes a round disk") {
  {
    MeshBuffers M = testmesh::polarDisk(5, 20);
    IntrinsicTriangulation T = buildIntrinsicTriangulation(M);
    FlowResult R = runRicciFlow(T, FlowOptions{});
    CHECK(R.maxError <= 1e-9);
    for (double x : R.u) CHECK(std::fabs(x) < 1e-9);
  }
  {
    const int rings = 8, m = 32;
    const double phiMax = 1.2;
    MeshBuffers M = testmesh::sphericalCap(rings, m, phiMax);
    IntrinsicTriangulation T = buildIntrinsicTriangulation(M);
    FlowResult R = runRicciFlow(T, FlowOptions{});
    CHECK(R.maxError <= 1e-9);
    CHECK(R.gaussBonnetError <= 1e-9);
    std::printf("cap: iterations %d, flips %lld, residuals:", R.iterations, R.flips);
    for (double r : R.residuals) std::printf(" %.3e", r);
    std::printf("\n");
    LayoutResult L = layoutFlat(T, R.u);
    CHECK(L.invertedTriangles == 0);
    CHECK(L.boundaryCrossings == 0);
    CHECK(L.maxEdgeLengthError < 1e-9);
    // Boundary on a circle centred at the image of the pole (vertex 0).
    const double cx = L.xy[0], cy = L.xy[1];
    double rmin = 1e300, rmax = 0;
    for (int j = 0; j < m; ++j) {
      const int v = 1 + (rings - 1) * m + j;
      const double r = std::hypot(L.xy[2 * v] - cx, L.xy[2 * v + 1] - cy);
      rmin = std::min(rmin, r);
      rmax = std::max(rmax, r);
    }
    CHECK((rmax - rmin) / rmax < 1e-9);
    // Stereographic projection: ring radii proportional to tan(phi/2), to discretization error.
    for (int k = 1; k < rings; ++k) {
      const int v = 1 + (k - 1) * m;
      const double r = std::hypot(L.xy[2 * v] - cx, L.xy[2 * v + 1] - cy) / rmax;
      const double expect = std::tan(0.5 * phiMax * k / rings) / std::tan(0.5 * phiMax);
      CHECK(std::fabs(r - expect) < 0.03);
    }
  }
}
