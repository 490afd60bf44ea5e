// Benchmark quality tool: the ONE measure applied to every mesher's output (ours and the peers').
//
//   quality_tool OUT [REF] [--samples N] [--feature-angle DEG] [--seed S]
//
// Reads OUT (and the reference input REF) with our readers (any of OBJ/OFF/STL/PLY) and prints one
// JSON line: triangles, vertices, angles (min, max, mean per-triangle min, % of triangles with min
// angle below 20/26/30°), edge lengths, Delaunay edge fraction, topology (components, boundary
// loops, χ, genus, non-manifold edges), and with REF: the sampled two-sided Hausdorff distance
// relative to REF's bounding-box diagonal, and the fraction of REF's sharp-edge samples kept.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/cli_util.h"
#include "mesh/mesh_io.h"
#include "quality/metrics.h"

using namespace conformesh;
using conformesh::cli::jsonNumber;

namespace {

MeshBuffers load(const std::string& path) {
  std::vector<uint8_t> bytes = cli::readFileBytes(path);
  ReadOptions opt;
  opt.fileName = path;
  return readMesh(bytes, opt).mesh;
}

std::string topologyJson(const quality::TopologySummary& t) {
  return "{\"vertices\":" + std::to_string(t.vertices) + ",\"edges\":" + std::to_string(t.edges) +
         ",\"faces\":" + std::to_string(t.faces) + ",\"components\":" + std::to_string(t.components) +
         ",\"boundaryLoops\":" + std::to_string(t.boundaryLoops) + ",\"euler\":" + std::to_string(t.euler) +
         ",\"genus\":" + std::to_string(t.genus) + ",\"nonManifoldEdges\":" + std::to_string(t.nonManifoldEdges) + "}";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    cli::Args a = cli::parseArgs(args, {"--samples", "--feature-angle", "--seed"}, {});
    if (a.positional.empty() || a.positional.size() > 2) {
      std::fprintf(stderr, "usage: quality_tool OUT [REF] [--samples N] [--feature-angle DEG] [--seed S]\n");
      return 2;
    }
    MeshBuffers out = load(a.positional[0]);
    quality::AngleStats an = quality::angleStats(out);
    quality::EdgeStats ed = quality::edgeStats(out);
    quality::TopologySummary to = quality::topologySummary(out);
    std::string hist;
    for (int i = 0; i < 13; ++i) hist += (i ? "," : "") + std::to_string(an.minAngleHistogram[i]);
    std::string json = "{\"triangles\":" + std::to_string(an.triangles) +
                       ",\"vertices\":" + std::to_string(to.vertices) +
                       ",\"degenerateTriangles\":" + std::to_string(an.degenerateTriangles) +
                       ",\"minAngle\":" + jsonNumber(an.minAngle) + ",\"maxAngle\":" + jsonNumber(an.maxAngle) +
                       ",\"meanMinAngle\":" + jsonNumber(an.meanMinAngle) +
                       ",\"pctBelow20\":" + jsonNumber(an.pctBelow20) + ",\"pctBelow26\":" + jsonNumber(an.pctBelow26) +
                       ",\"pctBelow30\":" + jsonNumber(an.pctBelow30) + ",\"minAngleHistogram5deg\":[" + hist + "]" +
                       ",\"edgeLength\":{\"min\":" + jsonNumber(ed.minLength) + ",\"max\":" + jsonNumber(ed.maxLength) +
                       ",\"mean\":" + jsonNumber(ed.meanLength) + "},\"delaunayEdgeFraction\":" +
                       jsonNumber(ed.delaunayFraction) + ",\"diagonal\":" + jsonNumber(quality::boundingBox(out).diagonal()) +
                       ",\"topology\":" + topologyJson(to);
    if (a.positional.size() == 2) {
      MeshBuffers ref = load(a.positional[1]);
      quality::HausdorffOptions ho;
      ho.samplesPerSide = size_t(a.number("--samples", 200000));
      ho.seed = uint64_t(a.number("--seed", 1));
      ho.computeMean = true;  // meanDistanceRel below
      quality::HausdorffResult h = quality::hausdorffDistance(out, ref, ho);
      quality::FeatureOptions fo;
      fo.featureAngle = a.number("--feature-angle", 60);
      fo.outputFeatureAngle = fo.featureAngle / 2;
      quality::FeatureResult fr = quality::featurePreservation(out, ref, fo);
      json += ",\"reference\":{\"triangles\":" + std::to_string(ref.triangleCount()) +
              ",\"topology\":" + topologyJson(quality::topologySummary(ref)) + "}" +
              ",\"hausdorffRel\":" + jsonNumber(h.relative) + ",\"hausdorff\":" + jsonNumber(h.hausdorff) +
              ",\"outToRefRel\":" + jsonNumber(h.diagonal > 0 ? h.aToB / h.diagonal : 0) +
              ",\"refToOutRel\":" + jsonNumber(h.diagonal > 0 ? h.bToA / h.diagonal : 0) +
              ",\"meanDistanceRel\":" +
              jsonNumber(h.diagonal > 0 ? 0.5 * (h.meanAToB + h.meanBToA) / h.diagonal : 0) +
              ",\"hausdorffSamples\":" + std::to_string(h.samplesA + h.samplesB) +
              ",\"features\":{\"featureAngle\":" + jsonNumber(fo.featureAngle) +
              ",\"referenceEdges\":" + std::to_string(fr.referenceFeatureEdges) +
              ",\"outputEdges\":" + std::to_string(fr.outputFeatureEdges) +
              ",\"samples\":" + std::to_string(fr.samples) + ",\"keptFraction\":" + jsonNumber(fr.fractionKept) +
              ",\"maxDistanceRel\":" + jsonNumber(h.diagonal > 0 ? fr.maxDistance / h.diagonal : 0) + "}";
    }
    json += "}";
    std::printf("%s\n", json.c_str());
    return 0;
  } catch (const Error& e) {
    return cli::reportError(e.status(), true);
  } catch (const std::exception& e) {
    return cli::reportError(Status{Code::InternalError, Stage::Report, e.what()}, true);
  }
}
