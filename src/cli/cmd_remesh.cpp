// conformesh remesh: remesh a surface mesh file and print the quality report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/cli_util.h"
#include "cli/command.h"
#include "mesh/mesh_io.h"
#include "remesh/remesh.h"

namespace conformesh::cli {
namespace {

std::string reportJson(const RemeshReport& r) {
  std::string s = "{";
  auto num = [&](const char* k, double v) { s += std::string("\"") + k + "\":" + jsonNumber(v) + ","; };
  num("triangles", double(r.triangles));
  num("vertices", double(r.vertices));
  num("minAngle", r.minAngle);
  num("maxAngle", r.maxAngle);
  num("meanMinAngle", r.meanMinAngle);
  num("pctBelow20", r.pctBelow20);
  num("pctBelow26", r.pctBelow26);
  num("pctBelow30", r.pctBelow30);
  num("pctMinAtLeast40", r.pctMinAtLeast40);
  num("pctMinAtLeast50", r.pctMinAtLeast50);
  num("minAngleOutsideExempt", r.minAngleOutsideExempt);
  num("trianglesBelowBoundOutsideExempt", double(r.trianglesBelowBoundOutsideExempt));
  s += "\"exemptCorners\":[";
  for (size_t i = 0; i < r.exemptCorners.size(); ++i) {
    const auto& c = r.exemptCorners[i];
    s += (i ? "," : "") + std::string("{\"vertex\":") + std::to_string(c.inputVertex) +
         ",\"angle\":" + jsonNumber(c.angleDeg) + ",\"triangles\":[";
    for (size_t k = 0; k < c.triangles.size(); ++k) s += (k ? "," : "") + std::to_string(c.triangles[k]);
    s += "]}";
  }
  s += "],";
  num("hausdorffRel", r.hausdorffRel);
  num("maxDistanceToInputRel", r.maxDistanceToInputRel);
  num("meanEdgeLength", r.meanEdgeLength);
  num("targetEdgeLength", r.targetEdgeLength);
  num("delaunayFraction", r.delaunayFraction);
  num("featureCurves", double(r.featureCurves));
  num("featureCurvesKept", double(r.featureCurvesKept));
  num("seamEdges", double(r.seamEdges));
  num("patches", double(r.patches));
  s += "\"flowIterations\":[";
  for (size_t i = 0; i < r.flowIterations.size(); ++i) s += (i ? "," : "") + std::to_string(r.flowIterations[i]);
  s += "],";
  num("conformingRounds", r.conformingRounds);
  num("certificateRounds", r.certificateRounds);
  num("estimatedTriangles", r.estimatedTriangles);
  num("optimizeMoves", double(r.optimizeMoves));
  num("optimizeFlips", double(r.optimizeFlips));
  num("repairMoves", double(r.repairMoves));
  s += "\"warnings\":[";
  for (size_t i = 0; i < r.warnings.size(); ++i) s += (i ? "," : "") + jsonString(r.warnings[i]);
  s += "],";
  s += std::string("\"topologyPreserved\":") + (r.topologyPreserved ? "true" : "false") + ",";
  s += "\"seconds\":{";
  for (Stage st : kRemeshStages) num(stageKey(st), *r.seconds.of(st));
  s += "\"total\":" + jsonNumber(r.seconds.total) + "}}";
  return s;
}

void printTable(const RemeshReport& r) {
  std::printf("%-28s %zu -> %zu\n", "triangles (in -> out)", r.inputTriangles, r.triangles);
  std::printf("%-28s %zu\n", "vertices", r.vertices);
  std::printf("%-28s %.2f / %.2f / %.2f deg\n", "angle min / mean-min / max", r.minAngle, r.meanMinAngle, r.maxAngle);
  std::printf("%-28s %.2f deg (%zu triangles below the bound)\n", "min angle outside exempt", r.minAngleOutsideExempt,
              r.trianglesBelowBoundOutsideExempt);
  std::printf("%-28s %.3f / %.3f / %.3f %%\n", "below 20 / 26 / 30 deg", r.pctBelow20, r.pctBelow26, r.pctBelow30);
  std::printf("%-28s %.2f / %.2f %%\n", "min angle >= 40 / 50 deg", r.pctMinAtLeast40, r.pctMinAtLeast50);
  std::printf("%-28s %zu\n", "exempt corners", r.exemptCorners.size());
  std::printf("%-28s %.3g (max vertex distance %.2g)\n", "Hausdorff / bbox diagonal", r.hausdorffRel,
              r.maxDistanceToInputRel);
  std::printf("%-28s %.4g (target %.4g)\n", "mean edge length", r.meanEdgeLength, r.targetEdgeLength);
  std::printf("%-28s %zu / %zu\n", "feature curves kept", r.featureCurvesKept, r.featureCurves);
  if (r.seamEdges > 0) std::printf("%-28s %zu\n", "attribute seam edges kept", r.seamEdges);
  std::printf("%-28s %zu (%zu curves, %zu samples)\n", "patches", r.patches, r.curves, r.curveSamples);
  std::printf("%-28s %s\n", "topology preserved", r.topologyPreserved ? "yes" : "NO");
  for (const auto& w : r.warnings) std::printf("%-28s %s\n", "warning", w.c_str());
  std::printf("%-28s", "seconds");
  for (Stage st : kRemeshStages) std::printf(" %s %.3f,", stageLabel(st), *r.seconds.of(st));
  std::printf(" total %.3f\n", r.seconds.total);
}

// Every flag of remesh, with RemeshOptions' defaults: what parsing accepts and --help prints.
std::vector<Flag> flags() {
  const RemeshOptions d;
  const auto num = [](double v) { return jsonNumber(v); };
  return {
      {"-o", "OUT", "write the output mesh; .obj, .off, .stl or .ply picks the format; without it no file is written", ""},
      {"--min-angle", "DEG", "angle bound of every output triangle outside exempt input corners, degrees in [0, 34]",
       num(d.minAngleDeg)},
      {"--edge-length", "L", "target edge length in flat regions, in the input's units; 0: --edge-length-rel",
       num(d.targetEdgeLength)},
      {"--edge-length-rel", "R", "target edge length as a fraction of the bounding-box diagonal",
       num(d.targetEdgeLengthRel)},
      {"--feature-angle", "DEG", "edges whose dihedral angle exceeds this (degrees) may be features",
       num(d.featureAngleDeg)},
      {"--min-feature-length", "L",
       "shortest chain of sharp edges kept as a crease, in the input's units; < 0: twice the target edge "
       "length; 0: every sharp edge",
       num(d.minFeatureLength)},
      {"--min-patch-width", "W",
       "merge patches narrower than this into a neighbour, in the input's units; < 0: a twentieth of the "
       "target edge length; 0: keep every patch",
       num(d.minPatchWidth)},
      {"--chord-tol", "T",
       "chord deviation bound of the curvature sizing, in the input's units; < 0: " + num(d.chordToleranceRel) +
           " times the diagonal; 0: no curvature sizing",
       num(d.chordTolerance)},
      {"--max-error", "D",
       "error-driven remeshing: the largest Hausdorff distance to the input, in the input's units; sizes grow "
       "as large as it allows, every sharp edge is a crease (the edge length then only scales the cuts and the "
       "smallest edge); 0: off",
       num(d.maxError)},
      {"--max-error-rel", "R", "--max-error as a fraction of the bounding-box diagonal; 0: off", num(d.maxErrorRel)},
      {"--boundary", "free|corners|circle", "the boundary condition each patch's flattening tries first",
       boundaryFlagValue(d.boundary)},
      {"--max-triangles", "N", "fail with TooLarge when the output would have more triangles",
       num(double(d.maxTriangles))},
      {"--max-vertices", "N", "fail with TooLarge when the output would have more vertices", num(double(d.maxVertices))},
      {"--optimize-iterations", "N", "passes of the optimization (a cap), an integer >= 0",
       num(d.optimizeIterations)},
      {"--optimize-tolerance", "T", "stop optimizing when a pass gains less than this fraction of the mean min angle",
       num(d.optimizeTolerance)},
      {"--threads", "N",
       "threads over the patches and the report's distances, an integer >= 0; 0: the hardware's concurrency; "
       "the output is the same for every count",
       num(d.threads)},
      {"--no-optimize", "", "skip the optimization (vertex moves and flips judged in 3D)", ""},
      {"--no-attributes", "",
       "drop the input's uvs, normals, colours and other vertex data instead of interpolating them onto the "
       "output (and keeping their seams as curves)",
       ""},
      {"--no-hausdorff", "", "leave the Hausdorff distance out of the report (it costs time on big meshes)", ""},
      {"--json", "", "print the report, or the error, as one JSON object on stdout", ""},
      {"--keep-defective", "", "write the output even when its topology is not the input's (still exit 1)", ""},
      {"--force-topology-defect", "", "break the output on purpose, to test the topology check", ""},
  };
}

int run(const std::vector<std::string>& argv) {
  bool json = false;
  for (const auto& a : argv) json = json || a == "--json";
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1) fail(Code::InvalidArgument, Stage::Api, "remesh needs exactly one input file");
    if (args.has("--edge-length") && args.has("--edge-length-rel"))
      fail(Code::InvalidArgument, Stage::Api, "give --edge-length or --edge-length-rel, not both");
    RemeshOptions opt;
    opt.minAngleDeg = args.number("--min-angle", opt.minAngleDeg);
    opt.targetEdgeLength = args.number("--edge-length", opt.targetEdgeLength);
    opt.targetEdgeLengthRel = args.number("--edge-length-rel", opt.targetEdgeLengthRel);
    opt.featureAngleDeg = args.number("--feature-angle", opt.featureAngleDeg);
    opt.minFeatureLength = args.number("--min-feature-length", opt.minFeatureLength);
    opt.minPatchWidth = args.number("--min-patch-width", opt.minPatchWidth);
    opt.chordTolerance = args.number("--chord-tol", opt.chordTolerance);
    if (args.has("--max-error") && args.has("--max-error-rel"))
      fail(Code::InvalidArgument, Stage::Api, "give --max-error or --max-error-rel, not both");
    opt.maxError = args.number("--max-error", opt.maxError);
    opt.maxErrorRel = args.number("--max-error-rel", opt.maxErrorRel);
    opt.computeHausdorff = !args.has("--no-hausdorff");
    opt.optimize = !args.has("--no-optimize");
    opt.carryAttributes = !args.has("--no-attributes");
    opt.keepDefectiveOutput = args.has("--keep-defective");
    opt.forceTopologyDefect = args.has("--force-topology-defect");
    // a count out of range is passed on for remesh to reject; a fractional one is rejected here
    const double iterations = args.number("--optimize-iterations", opt.optimizeIterations);
    if (iterations != std::floor(iterations))
      fail(Code::InvalidArgument, Stage::Api, "option --optimize-iterations needs an integer");
    opt.optimizeIterations = std::abs(iterations) <= 1e6 ? int(iterations) : -1;
    opt.optimizeTolerance = args.number("--optimize-tolerance", opt.optimizeTolerance);
    const double threads = args.number("--threads", opt.threads);
    if (threads != std::floor(threads)) fail(Code::InvalidArgument, Stage::Api, "option --threads needs an integer");
    opt.threads = std::abs(threads) <= 1e6 ? int(threads) : -1;
    opt.boundary = boundaryFlag(args, boundaryFlagValue(opt.boundary));
    // limits: 0 and negative values are rejected by remesh (InvalidArgument), never "unlimited"
    auto limit = [&](const char* flag, size_t fallback) {
      double v = args.number(flag, double(fallback));
      return v >= 1 ? size_t(std::min(v, 1e18)) : size_t(0);
    };
    opt.maxTriangles = limit("--max-triangles", opt.maxTriangles);
    opt.maxVertices = limit("--max-vertices", opt.maxVertices);
    const std::string& inPath = args.positional[0];
    ReadOptions ro;
    ro.fileName = inPath;
    ReadResult rr = readMesh(readFileBytes(inPath), ro);
    RemeshResult r = remesh(rr.mesh, opt);
    // a failed result has a mesh only with --keep-defective: it is written, and still an error
    if (!r.status.ok() && r.mesh.triangles.empty()) return reportError(r.status, json);
    std::string out = args.get("-o");
    if (!out.empty()) {
      auto dot = out.rfind('.');
      MeshFormat f = formatFromName(dot == std::string::npos ? "" : out.substr(dot));
      if (f == MeshFormat::Auto) fail(Code::InvalidArgument, Stage::Write, "-o: unknown extension (obj, off, stl, ply)");
      writeFileBytes(out, writeMesh(r.mesh, f));
    }
    if (!r.status.ok()) return reportError(r.status, json);
    if (json) std::printf("%s\n", reportJson(r.report).c_str());
    else printTable(r.report);
    return 0;
  } catch (const Error& e) {
    return reportError(e.status(), json);
  }
}

const CommandRegistrar registrar({"remesh", "remesh IN [-o OUT] [options]",
                                  "remesh a surface: conformal flattening per patch, planar Delaunay refinement, lift",
                                  flags, run});

}  // namespace
}  // namespace conformesh::cli
