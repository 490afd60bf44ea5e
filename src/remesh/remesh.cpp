#include "remesh/remesh.h"

#include <array>
#include <string>

#include "core/detmath.h"
#include "features/curve_mesh.h"
#include "mesh/mesh_attributes.h"
#include "remesh/carry_attributes.h"
#include "remesh/certificate.h"
#include "remesh/curve_samples.h"
#include "remesh/flatten_patches.h"
#include "remesh/limits.h"
#include "remesh/max_error.h"
#include "remesh/pipeline.h"
#include "remesh/prepare.h"
#include "remesh/repair.h"
#include "remesh/report.h"
#include "remesh/rounds.h"
#include "remesh/stitch.h"

namespace conformesh {
namespace {

using namespace pipeline;

// Passes of the last repair over the triangles still below the bound (a hard cap; a pass that
// moves nothing ends it). Each pass moves a vertex by a fraction of its star at most, and making
// room takes a few passes.
constexpr int kRepairRounds = 32;
// The last repair may move a star this fraction of the chord tolerance from the input (besides
// as far as it was; remesh/repair.h): 2.5e-4 of the diagonal by default, below the output's
// distance to the input elsewhere (~1e-3; docs/decisions/0013).
constexpr double kRepairDeviationFloor = 0.25;

// What the certificate left below the bound: free vertices (not on a feature or boundary curve,
// not a corner) moved over the surface in 3D (remesh/repair.h).
// Returns the triangles left below the bound.
size_t repairBelowBound(const Surface& surf, const CurveSamples& cs, const ExemptCorners& exempt, const RemeshOptions& opt,
                        BestRound& best, RemeshReport& rep) {
  MeshBuffers& out = best.out;
  std::vector<uint8_t> pinned(out.vertexCount(), 0);
  for (size_t c = 0; c < surf.seg.curves.size(); ++c)
    if (surf.seg.curves[c].kind != F::EdgeKind::Cut)
      for (uint32_t s : cs.cm.curveSamples[c])
        if (s < pinned.size()) pinned[s] = 1;
  for (uint32_t s : cs.cm.cornerSample)
    if (s < pinned.size()) pinned[s] = 1;
  for (size_t v = 0; v < pinned.size(); ++v) pinned[v] |= exempt.vertex[v];
  const auto isBad = [&](size_t t) { return exempt.bad(out, t); };
  // a repaired star may always be a quarter of the chord tolerance from the input
  const repair::RepairStats rs = repair::relaxBelowBound(out, best.vertexFace, best.triPatch, pinned, surf.graphMesh(),
                                                         surf.seg.facePatch, isBad, opt.minAngle, kRepairRounds,
                                                         kRepairDeviationFloor * surf.chordTolerance);
  rep.repairMoves = rs.moves;
  if (rs.rounds >= kRepairRounds && rs.left > 0)
    rep.warnings.push_back("repair stopped at its cap of " + std::to_string(kRepairRounds) + " passes with " +
                           std::to_string(rs.left) + " triangles below the bound");
  return rs.left;
}

// The pipeline of ../shared/DESIGN.md in the order of CONFORMESH_REMESH_STAGES (core/stages.h),
// each stage in its own file (pipeline.h).
RemeshResult run(const MeshBuffers& input, const RemeshOptions& opt, const ProgressFn& progressFn) {
  const Progress progress{progressFn};
  StageClock clock(Stage::Validate);
  const auto begin = [&](Stage s) {
    clock.enter(s);
    progress.check(s, 0);
  };
  RemeshReport rep;
  checkOptions(opt);

  begin(Stage::Validate);
  ValidatedMesh vm = validate(input);
  rep.inputTriangles = vm.buffers.triangleCount();
  rep.inputVertices = vm.buffers.vertexCount();
  for (const auto& wn : vm.report.warnings) rep.warnings.push_back(wn.message);

  begin(Stage::Segment);
  Surface surf = prepareSurface(std::move(vm), input, opt, progress, rep, clock);

  begin(Stage::Flatten);
  Meshing m;
  m.patches = flattenPatches(surf, opt, progress, rep);
  // the estimate of the patches the flattening made: its cuts are borders the refinement samples
  // and grades towards like any other, narrow strips between them included (the one before the
  // flattening, of the segmentation's patches, bounded the run: prepareSurface)
  rep.estimatedTriangles = estimateOutput(surf.g, surf.seg, surf.sizing).triangles;

  begin(Stage::CurveMesh);
  m.samples.cm = F::sampleCurves(surf.g, surf.seg, surf.sizing);
  indexSamples(surf, m.samples);
  measureCorners(surf, opt.minAngle, m);

  // refine, lift, optimize, stitch and certificate in rounds (rounds.h)
  ExemptCorners exempt(opt.minAngle);
  BestRound best = meshRounds(surf, opt, progress, m, exempt, rep, clock, [&](BestRound& trial) {
    RemeshReport scratch;  // a trial: its moves and warnings are not the output's
    return repairBelowBound(surf, m.samples, exempt, opt, trial, scratch);
  });
  if (best.bad > 0) {
    begin(Stage::Repair);
    repairBelowBound(surf, m.samples, exempt, opt, best, rep);
  }
  if (opt.forceTopologyDefect) addNonManifoldEdge(best.out, best.vertexFace, exempt.vertex, best.triPatch);
  checkOutputCounts(best.out.vertexCount(), best.out.triangleCount(), opt);  // remesh/limits.h

  begin(Stage::Report);
  // The patches' work is done: their memory goes back to the heap first, where the report's
  // buffers find it (fresh pages cost a fault each).
  rep.patches = m.patches.size();
  for (const auto& w : m.patches) rep.flowIterations.push_back(w->flat.report.iterations);
  m.patches.clear();
  RemeshResult res;
  res.status = reportOutput(surf, m.samples, best.out, best.vertexFace, exempt, opt, rep);
  progress.check(Stage::Report, 1.0);
  rep.seconds = clock.seconds();
  res.mesh = std::move(best.out);
  res.report = std::move(rep);
  if (opt.patches) {
    res.patches = std::move(best.patches);
    for (auto& rp : res.patches)
      for (uint32_t& f : rp.layoutInputFace) f = surf.vm.faceToInput[surf.pre.faceOrigin[f]];
    res.patchOfTriangle = best.triPatch;
  }
  if (opt.surfacePoints || (opt.attributes && hasAttributes(input))) {  // remesh/carry_attributes.h
    std::vector<uint32_t> hint(best.vertexFace.size(), kNone);
    for (size_t v = 0; v < hint.size(); ++v)
      if (best.vertexFace[v] < surf.vm.buffers.triangleCount()) hint[v] = surf.vm.faceToInput[best.vertexFace[v]];
    CornerPoints cp = locateCorners(input, res.mesh, hint);
    if (opt.attributes) interpolateAttributes(input, cp, res.mesh);
    res.cornerInputFace = std::move(cp.face);
    res.cornerBarycentric = std::move(cp.barycentric);
  }
  return res;
}

}  // namespace

RemeshResult remesh(const MeshBuffers& input, const RemeshOptions& options, ProgressFn progress) {
  RemeshResult r;
  try {
    // attribute seams are kept as feature curves (remesh/carry_attributes.h)
    std::vector<std::array<uint32_t, 2>> seams;
    if (options.attributes) {
      checkAttributes(input, Stage::Api);
      seams = attributeSeams(input);
    }
    RemeshOptions withSeams;
    if (!seams.empty()) {
      withSeams = options;
      withSeams.featureEdges.insert(withSeams.featureEdges.end(), seams.begin(), seams.end());
    }
    const RemeshOptions& opt = seams.empty() ? options : withSeams;
    if (errorDriven(opt)) {
      checkOptions(opt);
      r = remeshWithinError(input, opt, [&](const RemeshOptions& o) { return run(input, o, progress); });
    } else {
      r = run(input, opt, progress);
    }
    r.report.seamEdges = seams.size();
  } catch (const Error& e) {
    r = RemeshResult{};
    r.status = e.status();
  } catch (const std::bad_alloc&) {
    r = RemeshResult{};
    r.status = Status{Code::TooLarge, Stage::Api, "out of memory"};
  } catch (const std::exception& e) {
    r = RemeshResult{};
    r.status = Status{Code::InternalError, Stage::Api, e.what()};
  }
  return r;
}

}  // namespace conformesh
