// conformesh flatten IN -o OUT.obj [--boundary circle|free|corners] [--corner-angle DEG] [--json]
//
// Conformal flattening of a disk-like patch (or a disk with holes): writes the input mesh with
// the planar coordinates as `vt` (OBJ). --json prints the report: iterations,
// maxCurvatureError, flips, seconds, invertedTriangles (of the intrinsic layout),
// inputTrianglesInvertedInUv (of the file written), angleDistortionMax, areaDistortionRange (and
// more); without --json a warning on stderr counts the inverted triangles of the file. corners:
// boundary vertices of the outer loop whose 3D angle differs from a straight angle by more than
// --corner-angle (default 30) keep their angle.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "cli/command.h"
#include "conformal/flatten.h"
#include "core/constants.h"
#include "mesh/mesh_io.h"

namespace conformesh::cli {
namespace {

const double kCornerAngleDeg = 30.0;

std::vector<Flag> flags() {
  const FlattenOptions d;
  return {
      {"-o", "OUT.obj", "the input mesh with the planar coordinates as vt (required)", ""},
      {"--boundary", "circle|free|corners",
       "circle: a round disk; free: u = 0 on the boundary; corners: corners keep their 3D angle",
       boundaryFlagValue(d.boundary)},
      {"--corner-angle", "DEG",
       "with --boundary corners: boundary vertices whose 3D angle differs from 180 degrees by more are corners",
       jsonNumber(kCornerAngleDeg)},
      {"--tolerance", "T", "stop at a curvature error max |K - Kbar| below this, radians", jsonNumber(d.tolerance)},
      {"--max-iterations", "N", "Newton iterations at most (then IterationLimit)", jsonNumber(d.maxIterations)},
      {"--no-flips", "", "no intrinsic Delaunay flips during the flow (to study the flow without them)", ""},
      {"--json", "", "print the report, or the error, as one JSON object on stdout", ""},
  };
}

int runFlatten(const std::vector<std::string>& argv) {
  bool json = false;
  for (const auto& a : argv) json = json || a == "--json";
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1 || !args.has("-o"))
      fail(Code::InvalidArgument, Stage::Api,
           "usage: conformesh flatten IN -o OUT.obj [--boundary circle|free|corners] [--corner-angle DEG] [--json]");
    const std::string in = args.positional[0], out = args.get("-o");
    FlattenOptions o;
    o.boundary = boundaryFlag(args, boundaryFlagValue(o.boundary));
    o.tolerance = args.number("--tolerance", o.tolerance);
    o.maxIterations = int(args.number("--max-iterations", o.maxIterations));
    o.flips = !args.has("--no-flips");
    ReadOptions ro;
    ro.fileName = in;
    ReadResult rr = readMesh(readFileBytes(in), ro);
    if (o.boundary == BoundaryCondition::Corners) {
      const double deg = args.number("--corner-angle", kCornerAngleDeg);
      if (!(deg > 0 && deg < 180)) fail(Code::InvalidArgument, Stage::Api, "--corner-angle must be in (0, 180) degrees");
      o.corners = detectCorners(rr.mesh, deg * kPi / 180.0);
    }
    FlatPatch P = flatten(rr.mesh, o);
    MeshBuffers m = rr.mesh;
    m.uvs = P.uv;
    m.attributes.clear();  // the file written holds the flattening's uvs only
    writeFileBytes(out, writeMesh(m, MeshFormat::Obj));
    const FlattenReport& R = P.report;
    if (json) {
      std::string s = "{";
      auto field = [&](const char* key, const std::string& value) {
        if (s.size() > 1) s += ",";
        s += jsonString(key) + ":" + value;
      };
      field("iterations", std::to_string(R.iterations));
      field("maxCurvatureError", jsonNumber(R.maxCurvatureError));
      field("flips", std::to_string(R.flips));
      field("euclideanFlips", std::to_string(R.euclideanFlips));
      field("seconds", jsonNumber(R.seconds));
      field("invertedTriangles", std::to_string(R.invertedTriangles));
      field("inputTrianglesInvertedInUv", std::to_string(R.inputTrianglesInvertedInUv));
      field("boundaryCrossings", std::to_string(R.boundaryCrossings));
      field("angleDistortionMax", jsonNumber(R.angleDistortionMax));
      field("angleDistortionMean", jsonNumber(R.angleDistortionMean));
      field("areaDistortionRange", jsonNumber(R.areaDistortionRange));
      field("gaussBonnetError", jsonNumber(R.gaussBonnetError));
      field("boundaryLoops", std::to_string(R.boundaryLoops));
      field("corners", std::to_string(o.corners.size()));
      std::string res = "[";
      for (size_t i = 0; i < R.residuals.size(); ++i) res += (i ? "," : "") + jsonNumber(R.residuals[i]);
      field("residuals", res + "]");
      std::printf("%s}\n", s.c_str());
    } else {
      std::printf("flattened %zu vertices, %zu triangles: %d Newton iterations, error %.3g, %lld flips, %.3f s -> %s\n",
                  rr.mesh.vertexCount(), rr.mesh.triangleCount(), R.iterations, R.maxCurvatureError, R.flips, R.seconds,
                  out.c_str());
    }
    if (R.inputTrianglesInvertedInUv > 0 && !json)
      std::fprintf(stderr, "conformesh: warning: %d triangles of %s are inverted in uv (vertex uv of input triangles; the layout has %d)\n",
                   R.inputTrianglesInvertedInUv, out.c_str(), R.invertedTriangles);
    return 0;
  } catch (const Error& e) {
    return reportError(e.status(), json);
  } catch (const std::bad_alloc&) {
    return reportError(Status{Code::TooLarge, Stage::Flatten, "out of memory"}, json);
  }
}

const CommandRegistrar registrar({"flatten",
                                  "flatten IN -o OUT.obj [--boundary circle|free|corners] [--corner-angle DEG] [--no-flips] [--json]",
                                  "conformal flattening (Ricci flow with intrinsic Delaunay flips); writes uv as vt",
                                  flags, &runFlatten});

}  // namespace
}  // namespace conformesh::cli
