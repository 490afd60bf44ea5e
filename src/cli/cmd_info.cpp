// conformesh info FILE [--json] [--weld TOL] [--format NAME]: validation and topology report.
//
// JSON (one object on stdout): vertices, faces, components, boundaryLoops, euler, genus,
// nonManifoldEdges, degenerateFaces, warnings — warnings an array of
// {"code": name, "stage": "read"|"validate", "count": n, "message": text}. See meshInfo() in
// mesh/topology.h for the counting rules. On failure: exit 1 and {"error":{...}} (cli::reportError).
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "cli/command.h"
#include "mesh/mesh_io.h"
#include "mesh/topology.h"

namespace conformesh::cli {
namespace {

struct Warning {
  std::string code, stage, message;
  size_t count;
};

std::string numberText(double v) { return jsonNumber(v); }

std::vector<Flag> flags() {
  const ReadOptions d;
  return {
      {"--weld", "TOL", "also weld vertices closer than this, in the input's units; 0: exact duplicates in STL only",
       jsonNumber(d.weldTolerance)},
      {"--format", "NAME", "read as obj, off, stl, stl-ascii, ply, ply-ascii or ply-be; auto: from the content",
       formatName(d.format)},
      {"--json", "", "print the report, or the error, as one JSON object on stdout", ""},
  };
}

int runInfo(const std::vector<std::string>& argv) {
  bool json = false;
  for (const auto& a : argv) json = json || a == "--json";
  try {
    Args args = parseArgs(argv, flags());
    if (args.positional.size() != 1)
      fail(Code::InvalidArgument, Stage::Api, "usage: conformesh info FILE [--json] [--weld TOL] [--format NAME]");
    const std::string& path = args.positional[0];
    ReadOptions ro;
    ro.fileName = path;
    ro.weldTolerance = args.number("--weld", ro.weldTolerance);
    if (ro.weldTolerance < 0) fail(Code::InvalidArgument, Stage::Api, "--weld needs a tolerance >= 0");
    if (args.has("--format")) {
      ro.format = formatFromName(args.get("--format"));
      if (ro.format == MeshFormat::Auto && args.get("--format") != "auto")
        fail(Code::InvalidArgument, Stage::Api, "unknown format '" + args.get("--format") + "'");
    }
    ReadResult rr = readMesh(readFileBytes(path), ro);
    MeshInfo info = meshInfo(rr.mesh);

    std::vector<Warning> warnings;
    for (const auto& w : rr.warnings) warnings.push_back({codeName(Code::Ok), stageName(Stage::Read), w, 1});
    for (const auto& w : info.warnings)
      warnings.push_back({codeName(w.code), stageName(Stage::Validate), w.message, w.count});

    if (json) {
      std::string out = "{";
      auto field = [&](const char* key, const std::string& value) {
        if (out.size() > 1) out += ",";
        out += jsonString(key) + ":" + value;
      };
      field("vertices", std::to_string(info.vertices));
      field("faces", std::to_string(info.faces));
      field("components", std::to_string(info.components));
      field("boundaryLoops", std::to_string(info.boundaryLoops));
      field("euler", std::to_string(info.euler));
      field("genus", numberText(info.genus));
      field("nonManifoldEdges", std::to_string(info.nonManifoldEdges));
      field("degenerateFaces", std::to_string(info.degenerateFaces));
      std::string ws = "[";
      for (size_t i = 0; i < warnings.size(); ++i) {
        const Warning& w = warnings[i];
        ws += (i ? "," : "") + std::string("{\"code\":") + jsonString(w.code) + ",\"stage\":" + jsonString(w.stage) +
              ",\"count\":" + std::to_string(w.count) + ",\"message\":" + jsonString(w.message) + "}";
      }
      field("warnings", ws + "]");
      std::printf("%s}\n", out.c_str());
    } else {
      const std::vector<std::pair<std::string, std::string>> rows = {
          {"file", path + " (" + formatName(rr.format) + ")"},
          {"vertices", std::to_string(info.vertices)},
          {"faces", std::to_string(info.faces)},
          {"components", std::to_string(info.components)},
          {"boundaryLoops", std::to_string(info.boundaryLoops)},
          {"euler", std::to_string(info.euler)},
          {"genus", numberText(info.genus)},
          {"nonManifoldEdges", std::to_string(info.nonManifoldEdges)},
          {"degenerateFaces", std::to_string(info.degenerateFaces)},
          {"warnings", std::to_string(warnings.size())},
      };
      for (const auto& r : rows) std::printf("%-17s %s\n", r.first.c_str(), r.second.c_str());
      for (const Warning& w : warnings)
        std::printf("  - %s [%s]: %s\n", w.code.c_str(), w.stage.c_str(), w.message.c_str());
    }
    return 0;
  } catch (const Error& e) {
    return reportError(e.status(), json);
  } catch (const std::bad_alloc&) {
    return reportError(Status{Code::TooLarge, Stage::Read, "out of memory"}, json);
  } catch (const std::exception& e) {
    return reportError(Status{Code::InternalError, Stage::Api, e.what()}, json);
  }
}

const CommandRegistrar registrar({"info", "info FILE [--json] [--weld TOL] [--format NAME]",
                                  "validation and topology report: vertices, faces, components, boundary loops, "
                                  "Euler characteristic, genus, non-manifold edges, degenerate faces, warnings",
                                  flags, runInfo});

}  // namespace
}  // namespace conformesh::cli
