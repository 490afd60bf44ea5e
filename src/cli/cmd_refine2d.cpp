// conformesh refine2d: planar Delaunay refinement of a Triangle .poly file.
#include <cstdio>
#include <string>

#include "cli/cli_util.h"
#include "cli/command.h"
#include "planar/poly_io.h"
#include "planar/refine.h"

namespace conformesh::cli {
namespace {

std::string meshText(const planar::PlanarMesh& m, bool off) {
  std::string s;
  s.reserve(m.vertexCount() * 48 + m.triangleCount() * 24);
  char buf[96];
  if (off) {
    std::snprintf(buf, sizeof buf, "OFF\n%zu %zu 0\n", m.vertexCount(), m.triangleCount());
    s += buf;
  }
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    std::snprintf(buf, sizeof buf, off ? "%.17g %.17g 0\n" : "v %.17g %.17g 0\n", m.points[2 * i], m.points[2 * i + 1]);
    s += buf;
  }
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    unsigned a = m.triangles[3 * t], b = m.triangles[3 * t + 1], c = m.triangles[3 * t + 2];
    if (off)
      std::snprintf(buf, sizeof buf, "3 %u %u %u\n", a, b, c);
    else
      std::snprintf(buf, sizeof buf, "f %u %u %u\n", a + 1, b + 1, c + 1);
    s += buf;
  }
  return s;
}

std::vector<Flag> flags() {
  const planar::RefineOptions d;
  return {
      {"-o", "OUT.obj|OUT.off", "write the planar mesh (z = 0); without it no file is written", ""},
      {"--min-angle", "DEG", "angle bound of every triangle that is not exempt, degrees in [0, 34]",
       jsonNumber(d.minAngleDeg)},
      {"--max-area", "A", "largest triangle area, in the input's units squared; 0: none; not with --max-edge",
       jsonNumber(d.maxArea)},
      {"--max-edge", "L", "largest edge length, in the input's units; 0: none; not with --max-area",
       jsonNumber(d.maxEdge)},
      {"--max-insertions", "N", "Steiner points at most (then IterationLimit, exit 3)",
       jsonNumber(double(d.maxInsertions))},
      {"--convex-hull", "", "the domain is the convex hull minus the holes (Triangle's -c)", ""},
      {"--holes-by-orientation", "", "counterclockwise loops bound the domain, clockwise loops in them are holes", ""},
      {"--circumcenters", "", "insert circumcenters instead of off-centers", ""},
      {"--json", "", "print the report, or the error, as one JSON object on stdout", ""},
  };
}

int run(const std::vector<std::string>& argv) {
  bool json = false;
  for (const auto& a : argv) json = json || a == "--json";
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1)
      fail(Code::InvalidArgument, Stage::Api, "refine2d needs exactly one input .poly file");
    if (args.has("--max-area") && args.has("--max-edge"))
      fail(Code::InvalidArgument, Stage::Api, "give --max-area or --max-edge, not both");
    planar::RefineOptions opt;
    opt.minAngleDeg = args.number("--min-angle", opt.minAngleDeg);
    opt.maxArea = args.number("--max-area", opt.maxArea);
    opt.maxEdge = args.number("--max-edge", opt.maxEdge);
    double cap = args.number("--max-insertions", double(opt.maxInsertions));
    if (!(cap >= 0)) fail(Code::InvalidArgument, Stage::Api, "--max-insertions must be >= 0");
    opt.maxInsertions = size_t(cap);
    opt.cdt.convexHull = args.has("--convex-hull");
    opt.cdt.holesByOrientation = args.has("--holes-by-orientation");
    opt.offcenters = !args.has("--circumcenters");
    std::string out = args.get("-o");
    bool off = false;
    if (!out.empty()) {
      auto ends = [&](const char* e) {
        std::string x(e);
        return out.size() >= x.size() && out.compare(out.size() - x.size(), x.size(), x) == 0;
      };
      if (ends(".off")) off = true;
      else if (!ends(".obj")) fail(Code::InvalidArgument, Stage::Api, "-o must name a .obj or .off file");
    }
    planar::Pslg pslg = planar::readPoly(readFileBytes(args.positional[0]));
    planar::RefineResult r = planar::refinePslg(pslg, opt);
    if (!out.empty()) {
      std::string text = meshText(r.mesh, off);
      writeFileBytes(out, std::vector<uint8_t>(text.begin(), text.end()));
    }
    if (json) {
      std::printf(
          "{\"triangles\":%zu,\"vertices\":%zu,\"minAngle\":%s,\"exemptTriangles\":%zu,\"insertions\":%zu,"
          "\"segmentSplits\":%zu,\"rejected\":%zu,\"seconds\":%s,\"status\":%s}\n",
          r.mesh.triangleCount(), r.mesh.vertexCount(), jsonNumber(r.minAngleDeg).c_str(), r.exemptTriangles,
          r.insertions, r.segmentSplits, r.rejected, jsonNumber(r.seconds).c_str(),
          jsonString(codeName(r.status.code)).c_str());
    } else {
      std::printf("%zu triangles, %zu vertices, min angle %.3f deg (%zu exempt), %.3f s\n", r.mesh.triangleCount(),
                  r.mesh.vertexCount(), r.minAngleDeg, r.exemptTriangles, r.seconds);
      if (!r.status.ok()) std::fprintf(stderr, "conformesh: %s\n", r.status.message.c_str());
    }
    return r.status.ok() ? 0 : 3;
  } catch (const Error& e) {
    return reportError(e.status(), json);
  }
}

const CommandRegistrar reg({"refine2d",
                            "refine2d IN.poly [-o OUT.obj|OUT.off] [--min-angle D] [--max-area A | --max-edge L] "
                            "[--convex-hull] [--holes-by-orientation] [--circumcenters] [--max-insertions N] [--json]",
                            "quality triangulation of a planar straight-line graph (Delaunay refinement)", flags,
                            run});

}  // namespace
}  // namespace conformesh::cli
