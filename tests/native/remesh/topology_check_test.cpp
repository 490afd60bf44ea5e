// remesh's topology check: an output whose topology differs from the input's is an error, never a
// success; RemeshOptions::forceTopologyDefect breaks the output on purpose to see the check fail.
#include <doctest/doctest.h>

#include <string>

#include "features/test_shapes.h"
#include "quality/metrics.h"
#include "remesh/remesh.h"

using namespace conformesh;

namespace {

RemeshOptions quickOptions() {
  RemeshOptions o;
  o.targetEdgeLengthRel = 0.1;
  o.computeHausdorff = false;
  return o;
}

}  // namespace

TEST_CASE("remesh: a broken output is InternalError with an empty mesh; keepDefectiveOutput returns it") {
  const MeshBuffers in = testshapes::cube(4);
  RemeshOptions o = quickOptions();
  const RemeshResult good = remesh(in, o);
  REQUIRE_MESSAGE(good.status.ok(), good.status.message);
  CHECK(good.report.topologyPreserved);

  o.forceTopologyDefect = true;
  const RemeshResult bad = remesh(in, o);
  CHECK(bad.status.code == Code::InternalError);
  CHECK(bad.status.stage == Stage::Report);
  INFO(bad.status.message);
  CHECK(bad.status.message.find("output topology differs from the input") == 0);
  CHECK(bad.status.message.find("1 boundary loops vs 0") != std::string::npos);
  CHECK(bad.status.message.find("1 non-manifold edge,") != std::string::npos);
  CHECK(bad.status.message.find("2 non-manifold vertices") != std::string::npos);
  CHECK(bad.mesh.triangles.empty());
  CHECK(bad.mesh.positions.empty());

  o.keepDefectiveOutput = true;
  const RemeshResult kept = remesh(in, o);
  CHECK(kept.status.code == Code::InternalError);
  CHECK(kept.status.message == bad.status.message);
  CHECK_FALSE(kept.report.topologyPreserved);
  // the good output and the one extra triangle on one extra vertex
  CHECK(kept.mesh.triangleCount() == good.mesh.triangleCount() + 1);
  CHECK(kept.mesh.vertexCount() == good.mesh.vertexCount() + 1);
  CHECK(kept.report.triangles == kept.mesh.triangleCount());
  const quality::TopologySummary t = quality::topologySummary(kept.mesh);
  CHECK(t.nonManifoldEdges == 1);
  CHECK(t.boundaryLoops == 1);

  // asking for the defective output changes nothing when there is no defect
  o.forceTopologyDefect = false;
  const RemeshResult same = remesh(in, o);
  CHECK(same.status.ok());
  CHECK(same.mesh.positions == good.mesh.positions);
  CHECK(same.mesh.triangles == good.mesh.triangles);
}
