// Benchmark input preparation with our own readers/writers, so every tool gets identical bytes.
//
//   bench_prep convert IN OUT            (format of OUT from its extension: .obj .off .stl .ply)
//   bench_prep subdivide IN OUT [--levels K]
//       K rounds of 1-to-4 midpoint subdivision (each edge split at its midpoint, shared by both
//       faces; the surface does not move). Faces ×4 per round.
//
// Prints one JSON line: vertices, triangles, diagonal (bounding box of the output).
#include <cstdio>
#include <exception>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli/cli_util.h"
#include "mesh/mesh_io.h"
#include "quality/metrics.h"

using namespace conformesh;

namespace {

MeshBuffers subdivide(const MeshBuffers& in) {
  MeshBuffers out;
  out.positions = in.positions;
  std::unordered_map<uint64_t, uint32_t> mid;
  mid.reserve(in.triangles.size());
  auto midpoint = [&](uint32_t a, uint32_t b) {
    uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    uint32_t id = uint32_t(out.positions.size() / 3);
    for (int k = 0; k < 3; ++k) out.positions.push_back(0.5 * (in.positions[3 * size_t(a) + k] + in.positions[3 * size_t(b) + k]));
    mid.emplace(key, id);
    return id;
  };
  out.triangles.reserve(4 * in.triangles.size());
  for (size_t f = 0; f < in.triangleCount(); ++f) {
    uint32_t a = in.triangles[3 * f], b = in.triangles[3 * f + 1], c = in.triangles[3 * f + 2];
    uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.triangles.insert(out.triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    cli::Args a = cli::parseArgs(args, {"--levels"}, {});
    if (a.positional.size() != 3 || (a.positional[0] != "convert" && a.positional[0] != "subdivide")) {
      std::fprintf(stderr, "usage: bench_prep convert IN OUT | bench_prep subdivide IN OUT [--levels K]\n");
      return 2;
    }
    std::vector<uint8_t> bytes = cli::readFileBytes(a.positional[1]);
    ReadOptions ro;
    ro.fileName = a.positional[1];
    ro.readUvs = false;
    MeshBuffers mesh = readMesh(bytes, ro).mesh;
    if (a.positional[0] == "subdivide") {
      int levels = int(a.number("--levels", 1));
      if (levels < 0 || levels > 6) fail(Code::InvalidArgument, Stage::Api, "--levels must be in [0, 6]");
      for (int i = 0; i < levels; ++i) mesh = subdivide(mesh);
    }
    MeshFormat format = formatFromName(a.positional[2]);
    if (format == MeshFormat::Auto) fail(Code::InvalidArgument, Stage::Api, "unknown output extension: " + a.positional[2]);
    cli::writeFileBytes(a.positional[2], writeMesh(mesh, format));
    std::printf("{\"vertices\":%zu,\"triangles\":%zu,\"diagonal\":%s}\n", mesh.vertexCount(), mesh.triangleCount(),
                cli::jsonNumber(quality::boundingBox(mesh).diagonal()).c_str());
    return 0;
  } catch (const Error& e) {
    return cli::reportError(e.status(), true);
  } catch (const std::exception& e) {
    return cli::reportError(Status{Code::InternalError, Stage::Api, e.what()}, true);
  }
}
