// Compiled by CTest (public_header) with include/ alone on the path: the public header needs no
// internal header and no Eigen, and declares what a program uses.
#include <conformesh/conformesh.h>

namespace {

[[maybe_unused]] conformesh::Status remeshFile(const std::vector<uint8_t>& bytes, conformesh::MeshBuffers& out) {
  using namespace conformesh;
  ReadOptions ro;
  ro.fileName = "part.stl";
  const ReadResult read = readMesh(bytes, ro);
  RemeshOptions o;
  o.minAngle = 30;
  o.boundary = BoundaryCondition::Free;
  const RemeshResult r = remesh(read.mesh, o, [](Stage s, double f) { return stageName(s) != nullptr && f >= 0; });
  if (r.status.ok()) out = r.mesh;
  [[maybe_unused]] const std::vector<uint8_t> obj = writeMesh(out, MeshFormat::Obj);
  [[maybe_unused]] const double seconds = r.report.seconds.total + double(r.report.exemptCorners.size());
  return r.status;
}

}  // namespace
