// libFuzzer harness for the mesh readers (readMesh), one binary per format.
//
// Compiled once per format with -DFUZZ_FORMAT=<MeshFormat enumerator> (Auto, Obj, Off, StlAscii,
// StlBinary, PlyAscii, PlyBinaryLE, PlyBinaryBE) by tests/fuzz/run.sh, with
// -fsanitize=fuzzer,address,undefined. Properties checked on every input:
//   - readMesh returns or throws conformesh::Error; any other exception, a crash, a hang or a
//     sanitizer report is a bug; Code::InternalError is a bug too (a reader broke an invariant);
//   - a returned mesh is non-empty, finite, with every index in range;
//   - the mesh round-trips exactly through our OFF and binary PLY writers and readers (same
//     counts, same doubles, same indices);
//   - (Auto only) welding within a tolerance on the same bytes also returns cleanly.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "core/status.h"
#include "mesh/mesh_io.h"

#ifndef FUZZ_FORMAT
#define FUZZ_FORMAT Auto
#endif

using namespace conformesh;

namespace {

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "fuzz_read_mesh: property violated: %s\n", what);
  std::abort();
}

void checkMesh(const MeshBuffers& m) {
  if (m.positions.size() % 3 != 0 || m.triangles.size() % 3 != 0) bug("array sizes not multiples of 3");
  if (m.vertexCount() == 0 || m.triangleCount() == 0) bug("empty mesh returned without EmptyMesh");
  for (double x : m.positions)
    if (!std::isfinite(x)) bug("non-finite coordinate returned");
  for (uint32_t t : m.triangles)
    if (t >= m.vertexCount()) bug("index out of range returned");
  if (!m.uvs.empty() && m.uvs.size() != 2 * m.vertexCount()) bug("uv array of the wrong size");
}

void roundTrip(const MeshBuffers& m, MeshFormat format) {
  MeshBuffers plain;
  plain.positions = m.positions;
  plain.triangles = m.triangles;
  std::vector<uint8_t> bytes = writeMesh(plain, format);
  ReadOptions ro;
  ro.format = format;
  ReadResult back = readMesh(bytes, ro);  // must not throw: our own output
  if (back.mesh.positions != plain.positions) bug("round trip changed positions");
  if (back.mesh.triangles != plain.triangles) bug("round trip changed triangles");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ReadOptions opt;
  opt.format = MeshFormat::FUZZ_FORMAT;
  ReadResult r;
  try {
    r = readMesh(data, size, opt);
  } catch (const Error& e) {
    if (e.code() == Code::InternalError) bug(e.what());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exception: %s\n", e.what());
    bug("readMesh threw something other than conformesh::Error");
  }
  checkMesh(r.mesh);
  try {
    roundTrip(r.mesh, MeshFormat::Off);
    roundTrip(r.mesh, MeshFormat::PlyBinaryLE);
  } catch (const Error& e) {
    std::fprintf(stderr, "round trip error: %s\n", e.what());
    bug("our writer's output did not read back");
  }
#if defined(FUZZ_WELD)
  try {
    ReadOptions w = opt;
    w.weldTolerance = 1e-3;
    ReadResult rw = readMesh(data, size, w);
    checkMesh(rw.mesh);
    if (rw.mesh.vertexCount() > r.mesh.vertexCount()) bug("welding added vertices");
  } catch (const Error& e) {
    if (e.code() == Code::InternalError) bug(e.what());
  }
#endif
  return 0;
}
