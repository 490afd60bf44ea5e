// conformesh generate SHAPE -o FILE [--level N] [--format NAME]: write one of the generated
// surfaces of mesh/primitives.h (the sample meshes in web/samples were made with it).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "cli/command.h"
#include "mesh/mesh_io.h"
#include "mesh/primitives.h"

namespace conformesh::cli {
namespace {

const char* kShapes = "icosphere, torus, disk, annulus, cube, box-with-hole";

MeshBuffers makeShape(const std::string& shape, int level) {
  if (shape == "icosphere") return makeIcosphere(level);
  if (shape == "torus") return makeTorus(8 * level, 4 * level, 1.0, 0.35);
  if (shape == "disk") return makeDisk(2 * level, 8 * level, 1.0);
  if (shape == "annulus") return makeAnnulus(2 * level, 8 * level, 0.5, 1.0);
  if (shape == "cube") return makeCube(level, 1.0);
  if (shape == "box-with-hole") return makeBoxWithHole(level, 1.0, 0.4, 0.5);
  fail(Code::InvalidArgument, Stage::Api, "unknown shape '" + shape + "' (one of: " + kShapes + ")");
}

const int kLevel = 2;

std::vector<Flag> flags() {
  return {
      {"-o", "FILE", "the mesh file to write (required)", ""},
      {"--level", "N", "resolution, an integer in [1, 8]: higher is finer", std::to_string(kLevel)},
      {"--format", "NAME", "obj, off, stl, stl-ascii, ply, ply-ascii or ply-be", "from the extension of -o"},
  };
}

int runGenerate(const std::vector<std::string>& argv) {
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1 || !args.has("-o"))
      fail(Code::InvalidArgument, Stage::Api, "usage: conformesh generate SHAPE -o FILE [--level N] [--format NAME]");
    double level = args.number("--level", kLevel);
    if (level < 1 || level > 8 || level != int(level))
      fail(Code::InvalidArgument, Stage::Api, "--level must be an integer in [1, 8]");
    const std::string out = args.get("-o");
    MeshFormat format = formatFromName(args.has("--format") ? args.get("--format") : out);
    if (format == MeshFormat::Auto)
      fail(Code::InvalidArgument, Stage::Api, "cannot tell the output format from '" + out + "': use --format");
    MeshBuffers m = makeShape(args.positional[0], int(level));
    writeFileBytes(out, writeMesh(m, format));
    std::printf("%s: %zu vertices, %zu triangles (%s)\n", out.c_str(), m.vertexCount(), m.triangleCount(),
                formatName(format));
    return 0;
  } catch (const Error& e) {
    return reportError(e.status(), false);
  } catch (const std::exception& e) {
    return reportError(Status{Code::InternalError, Stage::Api, e.what()}, false);
  }
}

const CommandRegistrar registrar({"generate", "generate SHAPE -o FILE [--level N] [--format NAME]",
                                  "write a generated test surface (icosphere, torus, disk, annulus, cube, box-with-hole)",
                                  flags, runGenerate});

}  // namespace
}  // namespace conformesh::cli
