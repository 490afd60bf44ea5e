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

// A report field as JSON, by its C++ type (the rows of CONFORMESH_REMESH_REPORT).
std::string json(double v) { return jsonNumber(v); }
std::string json(size_t v) { return jsonNumber(double(v)); }
std::string json(uint32_t v) { return jsonNumber(v); }
std::string json(int v) { return jsonNumber(v); }
std::string json(bool v) { return v ? "true" : "false"; }
std::string json(const std::string& v) { return jsonString(v); }
std::string json(const ExemptCorner& c);
template <class T>
std::string json(const std::vector<T>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + json(v[i]);
  return s + "]";
}
std::string json(const StageSeconds& t) {
  std::string s = "{";
  for (Stage st : kRemeshStages) s += std::string("\"") + stageKey(st) + "\":" + jsonNumber(*t.of(st)) + ",";
  return s + "\"total\":" + jsonNumber(t.total) + "}";
}

// {"name":value,...} of the fields of `obj` a table lists: an exempt corner, the report (every
// field of CONFORMESH_REMESH_REPORT in its order).
void member(std::string& s, const char* name, const std::string& value) {
  s += std::string(s.empty() ? "{" : ",") + "\"" + name + "\":" + value;
}
#define CONFORMESH_JSON_FIELD(type, name, init) member(s, #name, json(obj.name));
std::string json(const ExemptCorner& obj) {
  std::string s;
  CONFORMESH_EXEMPT_CORNER(CONFORMESH_JSON_FIELD)
  return s + "}";
}
std::string reportJson(const RemeshReport& obj) {
  std::string s;
  CONFORMESH_REMESH_REPORT(CONFORMESH_JSON_FIELD)
  return s + "}";
}
#undef CONFORMESH_JSON_FIELD

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

// An option's default as --help shows it, and its flag's value read into it, by its C++ type
// (the rows of CONFORMESH_REMESH_OPTIONS).
std::string shown(double v) { return jsonNumber(v); }
std::string shown(int v) { return jsonNumber(v); }
std::string shown(size_t v) { return jsonNumber(double(v)); }
std::string shown(bool) { return ""; }
std::string shown(Boundary v) { return boundaryKey(v); }

void readFlag(const Args& args, const char* flag, double& v) { v = args.number(flag, v); }
//! A count out of range is passed on for remesh to reject; a fractional one is rejected here.
void readFlag(const Args& args, const char* flag, int& v) {
  const double d = args.number(flag, v);
  if (d != std::floor(d)) fail(Code::InvalidArgument, Stage::Api, std::string("option ") + flag + " needs an integer");
  v = std::abs(d) <= 1e6 ? int(d) : -1;
}
//! 0 and negative values become 0, which remesh rejects (InvalidArgument), never "unlimited".
void readFlag(const Args& args, const char* flag, size_t& v) {
  const double d = args.number(flag, double(v));
  v = d >= 1 ? size_t(std::min(d, 1e18)) : size_t(0);
}
void readFlag(const Args& args, const char* flag, bool& v) {
  if (args.has(flag)) v = std::string(flag).rfind("--no-", 0) != 0;
}
void readFlag(const Args& args, const char* flag, Boundary& v) { v = boundaryFlag(args, boundaryKey(v)); }

// Every flag of remesh: -o, a flag per option of CONFORMESH_REMESH_OPTIONS with its default, --json.
std::vector<Flag> flags() {
  const RemeshOptions d;
  std::vector<Flag> out = {
      {"-o", "OUT", "write the output mesh; .obj, .off, .stl or .ply picks the format; without it no file is written", ""}};
#define CONFORMESH_X(type, name, fallback, lo, hi, flag, value, help) \
  if (*flag) out.push_back({flag, value, help, shown(d.name)});
  CONFORMESH_REMESH_OPTIONS(CONFORMESH_X)
#undef CONFORMESH_X
  out.push_back({"--json", "", "print the report, or the error, as one JSON object on stdout", ""});
  return out;
}

int run(const std::vector<std::string>& argv) {
  bool json = false;
  for (const auto& a : argv) json = json || a == "--json";
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1) fail(Code::InvalidArgument, Stage::Api, "remesh needs exactly one input file");
    if (args.has("--edge-length") && args.has("--edge-length-rel"))
      fail(Code::InvalidArgument, Stage::Api, "give --edge-length or --edge-length-rel, not both");
    if (args.has("--max-error") && args.has("--max-error-rel"))
      fail(Code::InvalidArgument, Stage::Api, "give --max-error or --max-error-rel, not both");
    RemeshOptions opt;
#define CONFORMESH_X(type, name, fallback, lo, hi, flag, value, help) \
  if (*flag) readFlag(args, flag, opt.name);
    CONFORMESH_REMESH_OPTIONS(CONFORMESH_X)
#undef CONFORMESH_X
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
