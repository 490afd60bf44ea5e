// Degenerate but valid inputs (issue 8): each remeshes, or fails with a precise status; never a
// crash, a hang (a wall-clock cap through the progress callback) or a silently wrong output.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "features/test_shapes.h"
#include "quality/metrics.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {

MeshBuffers mesh(std::vector<double> p, std::vector<uint32_t> t) {
  MeshBuffers m;
  m.positions = std::move(p);
  m.triangles = std::move(t);
  return m;
}

// x-by-y grid of quads (two triangles each) over [0, w] × [0, h] in the plane z = 0.
MeshBuffers grid(int nx, int ny, double w, double h) {
  MeshBuffers m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.positions.insert(m.positions.end(), {w * i / nx, h * j / ny, 0.0});
  auto id = [&](int i, int j) { return uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

MeshBuffers transformed(MeshBuffers m, double scale, double offset) {
  for (double& x : m.positions) x = x * scale + offset;
  return m;
}

// Remesh at the 30 degree default bound with a wall-clock cap (the progress callback cancels after
// `capSeconds`), and require success.
RemeshResult remeshOk(const MeshBuffers& in, RemeshOptions o, double capSeconds = 60) {
  o.hausdorffSamples = 2000;
  const auto t0 = std::chrono::steady_clock::now();
  RemeshResult r = remesh(in, o, [&](Stage, double) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < capSeconds;
  });
  INFO("status " << std::string(codeName(r.status.code)) << ": " << r.status.message);
  REQUIRE(r.status.ok());
  return r;
}

RemeshOptions relative(double targetRel) {
  RemeshOptions o;
  o.targetEdgeLengthRel = targetRel;
  return o;
}

// A successful output: non-empty, finite, indices in range, manifold, the topology of the input,
// every vertex on the input surface (to 1e-9 of the diagonal, or a few units in the last place of
// the coordinates when they are large), and a truthful angle report: the triangles below the
// bound outside exempt corners are counted right (recomputed here), and there are none when
// `requireBound`.
void checkValidOutput(const MeshBuffers& in, const RemeshResult& r, double minAngle, bool requireBound = true) {
  const MeshBuffers& m = r.mesh;
  REQUIRE(m.triangleCount() > 0);
  for (double x : m.positions) REQUIRE(std::isfinite(x));
  for (uint32_t v : m.triangles) REQUIRE(v < m.vertexCount());
  auto ti = quality::topologySummary(in), to = quality::topologySummary(m);
  CHECK(to.nonManifoldEdges == 0);
  CHECK(r.report.topologyPreserved);
  CHECK(to.components == ti.components);
  CHECK(to.boundaryLoops == ti.boundaryLoops);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, big = 0;
  for (size_t v = 0; v < in.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], in.positions[3 * v + k]);
      hi[k] = std::max(hi[k], in.positions[3 * v + k]);
      big = std::max(big, std::abs(in.positions[3 * v + k]));
    }
  const double diag = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double ulps = 4 * big * std::numeric_limits<double>::epsilon();
  CHECK(r.report.maxDistanceToInputRel * diag <= 1e-9 * diag + ulps);
  std::vector<uint8_t> exempt(m.triangleCount(), 0);
  for (const auto& c : r.report.exemptCorners)
    for (uint32_t t : c.triangles) exempt[t] = 1;
  size_t below = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    double a[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) a[c][k] = m.positions[3 * m.triangles[3 * t + c] + k];
    double smallest = 180;
    for (int c = 0; c < 3; ++c) {
      const double* p = a[c];
      const double *q = a[(c + 1) % 3], *s = a[(c + 2) % 3];
      double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
      double cr = std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
      smallest = std::min(smallest, std::atan2(cr, u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) * 180 / 3.14159265358979323846);
    }
    if (!exempt[t] && smallest < minAngle - 1e-9) ++below;
  }
  CHECK(below == r.report.trianglesBelowBoundOutsideExempt);
  if (requireBound) CHECK(below == 0);
  CHECK(r.report.featureCurvesKept == r.report.featureCurves);
}

}  // namespace

TEST_CASE("degenerate input: a single triangle") {
  MeshBuffers in = mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  checkValidOutput(in, remeshOk(in, relative(0.1)), 30);
}

TEST_CASE("degenerate input: two triangles folded onto each other (dihedral angle 0)") {
  // (0,1,2) and (1,0,3) share edge 0-1; vertex 3 lies on the same side as 2: the second triangle
  // is the first folded over the shared edge (normals opposite).
  MeshBuffers in = mesh({0, 0, 0, 1, 0, 0, 0.4, 0.8, 0, 0.6, 0.7, 0}, {0, 1, 2, 1, 0, 3});
  RemeshResult r = remeshOk(in, relative(0.1));
  checkValidOutput(in, r, 30);
  CHECK(r.report.sharpEdges >= 1);  // the fold is a feature
}

TEST_CASE("degenerate input: a face with a 180 degree angle (three collinear vertices)") {
  // triangle A B C with M on A–B, split into A M C and M B C, and the zero-area face A B M that
  // CAD exports leave where a T-junction was closed. validate() drops it with a warning.
  MeshBuffers in = mesh({0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0}, {0, 1, 3, 1, 2, 3, 0, 2, 1});
  RemeshResult r = remeshOk(in, relative(0.1));
  checkValidOutput(mesh(in.positions, {0, 1, 3, 1, 2, 3}), r, 30);
  CHECK(!r.report.warnings.empty());
}

TEST_CASE("degenerate input: a very long thin strip (1000 x 1)") {
  // Failed before the reliability branch: the layout's boundary-crossing test counted disjoint
  // collinear pieces of the long straight sides as crossings (NumericalFailure from flatten).
  MeshBuffers in = grid(1000, 1, 1000.0, 1.0);
  RemeshOptions o;
  o.targetEdgeLength = 0.5;
  checkValidOutput(in, remeshOk(in, o), 30);
  checkValidOutput(in, remeshOk(in, relative(0.02)), 30);  // target 20, 20 times the width
}

TEST_CASE("degenerate input: coordinates around 1e6, features of size 1e-3") {
  MeshBuffers in = transformed(testshapes::cube(3), 1e-3, 1e6);
  checkValidOutput(in, remeshOk(in, relative(0.1)), 30);
}

TEST_CASE("degenerate input: a mesh 1e-9 in size") {
  MeshBuffers in = transformed(testshapes::cube(3), 1e-9, 0.0);
  // The bound is not required here: at this scale (and at 1e-6; not at 5e-10, 1e-8 or 2^-30) the
  // rounding leads to 4 triangles of 28.2 degrees with an edge on a cube edge (a patch boundary);
  // the certificate round makes it worse (8) and the best round is kept. A weakness of the
  // meshing loop, not of the scale (no absolute tolerance is involved). The report must say so.
  checkValidOutput(in, remeshOk(in, relative(0.1)), 30, false);
}
