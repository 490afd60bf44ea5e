#include "remesh/report.h"
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <unordered_map>

#include "core/parallel_for.h"
#include "quality/metrics.h"

namespace conformesh::pipeline {
namespace {

// Output vertices per chunk of the distance to the input (a fixed size: the same searches for
// every thread count).
constexpr size_t kDistanceChunk = 4096;

//! How the output's topology differs from the input's ("Euler characteristic 3 vs 2, 1
//! non-manifold edge"), or "" when it has the input's components, boundary loops and Euler
//! characteristic and no non-manifold edge or vertex.
std::string topologyDifference(const quality::TopologySummary& out, const quality::TopologySummary& in) {
  std::string s;
  const auto add = [&](const std::string& what) { s += (s.empty() ? "" : ", ") + what; };
  const auto count = [](size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  if (out.components != in.components) add(std::to_string(out.components) + " components vs " + std::to_string(in.components));
  if (out.boundaryLoops != in.boundaryLoops)
    add(std::to_string(out.boundaryLoops) + " boundary loops vs " + std::to_string(in.boundaryLoops));
  if (out.euler != in.euler) add("Euler characteristic " + std::to_string(out.euler) + " vs " + std::to_string(in.euler));
  if (out.genus >= 0 && in.genus >= 0 && out.genus != in.genus)
    add("genus " + std::to_string(out.genus) + " vs " + std::to_string(in.genus));
  if (out.nonManifoldEdges > 0) add(count(out.nonManifoldEdges, "non-manifold edge", "non-manifold edges"));
  if (out.nonManifoldVertices > 0) add(count(out.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices"));
  return s;
}

}  // namespace

Status reportOutput(const Surface& surf, const CurveSamples& cs, const MeshBuffers& out, const std::vector<uint32_t>& vertexFace,
                    ExemptCorners& exempt, const RemeshOptions& opt, RemeshReport& rep) {
  const MeshBuffers& in = surf.input();
  std::vector<double> triMinRad;  // per triangle, NaN when degenerate
  quality::AngleStats as;
  quality::EdgeTopology et;
  quality::TopologySummary ti;
  std::unique_ptr<quality::TriangleMeshDistance> dist;  // the input's, for the max vertex distance
  quality::HausdorffOptions ho;
  ho.samplesPerSide = opt.hausdorffSamples;
  ho.nearTriangleOfVertexA = &vertexFace;  // the input face each output vertex was lifted onto: a start
  ho.threads = unsigned(opt.threads);
  quality::HausdorffWork hw;
  // feature curves kept: every pair of consecutive samples is an output edge
  const auto countFeatureCurves = [&] {
    // (vertex -> neighbours in compressed rows: a hash set of every edge cost 5x more here)
    std::vector<uint32_t> nbrStart(out.vertexCount() + 1, 0), nbr(2 * out.triangles.size());
    for (uint32_t v : out.triangles) nbrStart[v + 1] += 2;
    for (size_t v = 0; v < out.vertexCount(); ++v) nbrStart[v + 1] += nbrStart[v];
    {
      std::vector<uint32_t> fill(nbrStart.begin(), nbrStart.end() - 1);
      for (size_t t = 0; t < out.triangles.size(); t += 3)
        for (int c = 0; c < 3; ++c) {
          uint32_t a = out.triangles[t + c], b = out.triangles[t + (c + 1) % 3];
          nbr[fill[a]++] = b;
          nbr[fill[b]++] = a;
        }
    }
    auto isEdge = [&](uint32_t a, uint32_t b) {
      return std::find(nbr.begin() + nbrStart[a], nbr.begin() + nbrStart[a + 1], b) != nbr.begin() + nbrStart[a + 1];
    };
    for (size_t c = 0; c < surf.seg.curves.size(); ++c) {
      if (surf.seg.curves[c].kind == F::EdgeKind::Cut) continue;
      ++rep.featureCurves;
      bool kept = true;
      const auto& ids = cs.cm.curveSamples[c];
      for (size_t i = 0; i + 1 < ids.size() && kept; ++i) {
        kept = isEdge(ids[i], ids[i + 1]);
      }
      rep.featureCurvesKept += kept;
    }
  };
  // the passes over the output and the input, and what the distances need, do not depend on each
  // other: side by side, the largest first (Hausdorff job 0: the larger mesh's tree, the output's)
  enum : int { kEdges = -1, kAngles = -2, kInputTree = -3, kInputTopology = -4, kFeatureCurves = -5 };
  std::vector<int> jobs = {kEdges, kAngles, kFeatureCurves, kInputTree, kInputTopology};
  if (opt.computeHausdorff) jobs = {0, kEdges, kAngles, 1, 2, 3, kFeatureCurves, kInputTree, kInputTopology};
  parallelFor(jobs.size(), unsigned(opt.threads), [&](size_t i) {
    switch (jobs[i]) {
      case kEdges: et = quality::edgeStatsAndTopology(out); break;
      case kAngles: as = quality::angleStats(out, &triMinRad); break;
      case kInputTree: dist = std::make_unique<quality::TriangleMeshDistance>(in); break;
      case kInputTopology: ti = quality::topologySummary(in); break;
      case kFeatureCurves: countFeatureCurves(); break;
      default: quality::hausdorffJob(hw, out, in, ho, size_t(jobs[i]));
    }
  });
  rep.triangles = out.triangleCount();
  rep.vertices = out.vertexCount();
  rep.minAngle = as.minAngle;
  rep.maxAngle = as.maxAngle;
  rep.meanMinAngle = as.meanMinAngle;
  rep.pctBelow20 = as.pctBelow20;
  rep.pctBelow26 = as.pctBelow26;
  rep.pctBelow30 = as.pctBelow30;
  if (as.triangles > 0) {
    size_t at40 = 0, at50 = 0;
    for (int b = 8; b < 13; ++b) at40 += as.minAngleHistogram[b];
    for (int b = 10; b < 13; ++b) at50 += as.minAngleHistogram[b];
    rep.pctMinAtLeast40 = 100.0 * double(at40) / double(as.triangles);
    rep.pctMinAtLeast50 = 100.0 * double(at50) / double(as.triangles);
  }
  rep.minAngleOutsideExempt = 180;
  exempt.indexWedges(surf, cs);
  std::unordered_map<uint32_t, size_t> cornerIndex;
  for (size_t i = 0; i < rep.exemptCorners.size(); ++i) cornerIndex[rep.exemptCorners[i].outputVertex] = i;
  for (size_t t = 0; t < out.triangleCount(); ++t) {
    const uint32_t* tv = &out.triangles[3 * t];
    bool ex = false;
    for (int c = 0; c < 3; ++c)
      if (exempt.vertex[tv[c]]) {
        ex = true;
        rep.exemptCorners[cornerIndex.at(tv[c])].triangles.push_back(uint32_t(t));
      }
    if (!ex) {
      const uint32_t corner = exempt.cornerOf(out, t);
      if (corner != kNone) {
        ex = true;
        rep.exemptCorners[cornerIndex.at(corner)].triangles.push_back(uint32_t(t));
      }
    }
    if (ex) continue;
    // the same value as triangleMinAngle (the same atan2s; degrees are monotone in radians)
    const double a = std::isnan(triMinRad[t]) ? triangleMinAngle(out, t) : triMinRad[t] * 180.0 / kPi;
    rep.minAngleOutsideExempt = std::min(rep.minAngleOutsideExempt, a);
    if (a < opt.minAngle) ++rep.trianglesBelowBoundOutsideExempt;
  }
  rep.meanEdgeLength = et.edges.meanLength;
  rep.delaunayFraction = et.edges.delaunayFraction;
  const quality::TopologySummary& to = et.topology;
  // a broken mesh is never a success: a defect here is a bug of the stitch or the repair
  const std::string defect = topologyDifference(to, ti);
  rep.topologyPreserved = defect.empty();
  Status topologyStatus;
  if (!defect.empty()) {
    topologyStatus = Status{Code::InternalError, Stage::Report, "output topology differs from the input: " + defect};
    if (!opt.keepDefectiveOutput) fail(topologyStatus.code, topologyStatus.stage, topologyStatus.message);
  }
  rep.sharpEdges = surf.seg.sharpEdgeCount;
  rep.cutEdges = surf.seg.cutEdgeCount;
  rep.droppedFeatureEdges = surf.seg.droppedFeatureEdges;
  rep.curves = surf.seg.curves.size();
  rep.curveSamples = cs.cm.samples.size();
  {
    // in chunks of a fixed size, each with its own running max: the same searches on any number
    // of threads, and the max of the chunks' maxima is the max over every vertex
    const size_t nv = out.vertexCount();
    std::vector<double> chunkWorst((nv + kDistanceChunk - 1) / kDistanceChunk, 0.0);
    parallelFor(chunkWorst.size(), unsigned(opt.threads), [&](size_t c) {
      double worst = 0;
      int64_t hint = -1;  // consecutive output vertices are near each other (curves, then patches)
      for (size_t v = c * kDistanceChunk; v < std::min(nv, (c + 1) * kDistanceChunk); ++v) {
        const Vec3 p = vec3At(out.positions, v);
        // the input face the vertex was lifted onto (or one beside its curve sample) bounds its
        // distance: at most the worst so far, the vertex cannot change the maximum
        if (vertexFace[v] < in.triangleCount()) {
          hint = vertexFace[v];
          if (dist->faceDistanceSquared(vertexFace[v], p) <= worst) continue;
        }
        auto hit = dist->closest(p, hint);
        hint = hit.primitive;
        worst = std::max(worst, hit.distanceSquared);
      }
      chunkWorst[c] = worst;
    });
    double worst = 0;
    for (double w : chunkWorst) worst = std::max(worst, w);
    rep.maxDistanceToInputRel = std::sqrt(worst) / surf.sizing.diagonal;
  }
  if (opt.computeHausdorff) rep.hausdorffRel = quality::hausdorffMeasure(hw, out, in, ho).relative;
  return topologyStatus;
}

}  // namespace conformesh::pipeline
