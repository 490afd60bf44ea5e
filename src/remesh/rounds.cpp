#include "remesh/rounds.h"

#include <algorithm>
#include <exception>
#include <string>

#include "core/parallel_for.h"
#include "remesh/mesh_patches.h"
#include "remesh/slide_samples.h"
#include "remesh/stitch.h"

namespace conformesh::pipeline {
namespace {

// Rounds of re-refining patches whose boundary got samples from a neighbour's segment splits.
constexpr int kConformingRounds = 8;
// Certificate rounds past the cap for a stitch defect still there, with its patches keeping their
// boundary: one opened it in most cases measured; a chord both patches drew across the two wedges
// at a spike tip of man (angle sum 133°, --feature-angle 20 --edge-length-rel 0.005) took four.
constexpr int kKeepBoundaryRounds = 4;
// A certificate round makes progress when it leaves at most this fraction of the best round's
// triangles below the bound: camelhead at 35° went 39, 19, 16, 15, 17, 11, 17 over its rounds,
// each a re-refinement of the patches with spots, for what the repair takes anyway
// (docs/decisions/0035).
constexpr double kRoundProgress = 0.8;

// optimizeMesh on every patch p with optimize[p] (its vertices active[p], empty: all), on the
// threads, report(i) on the calling thread after each; the report's counts added in patch order.
void optimizePatches(const Surface& surf, const RemeshOptions& opt, Meshing& m, const std::vector<uint8_t>& optimize,
                     const std::vector<std::vector<uint8_t>>& active, const std::function<void(size_t, size_t)>& report,
                     RemeshReport& rep) {
  std::vector<uint32_t> todo;
  for (uint32_t p = 0; p < m.patches.size(); ++p)
    if (optimize[p]) todo.push_back(p);
  // the largest first; an error is thrown in patch order, as a serial loop would
  std::vector<double> cost(todo.size());
  for (size_t i = 0; i < todo.size(); ++i) {
    const std::vector<uint8_t>& a = active[todo[i]];
    cost[i] = a.empty() ? double(m.patches[todo[i]]->planarPoints.size())
                        : double(std::count_if(a.begin(), a.end(), [](uint8_t x) { return x != 0; }));
  }
  const std::vector<size_t> byCost = largestFirst(cost);
  std::vector<OptimizeResult> done(todo.size());
  std::vector<std::exception_ptr> error(todo.size());
  parallelFor(
      todo.size(), unsigned(opt.threads),
      [&](size_t k) {
        const size_t i = byCost[k];
        try {
          done[i] = optimizeMesh(surf, opt, m.samples, *m.patches[todo[i]], active[todo[i]]);
        } catch (...) {
          error[i] = std::current_exception();
        }
      },
      [&](size_t finished) { report(finished, todo.size()); });
  for (const std::exception_ptr& e : error)
    if (e) std::rethrow_exception(e);
  for (size_t i = 0; i < done.size(); ++i) {
    rep.optimizeMoves += done[i].moves;
    rep.optimizeFlips += done[i].flips;
    rep.optimizeSplits += done[i].splits;
    rep.optimizeCollapses += done[i].collapses;
    if (done[i].splitsCapped)
      rep.warnings.push_back("patch " + std::to_string(todo[i]) + ": vertices added by the optimization stopped at their cap with triangles below the bound left");
  }
}

}  // namespace

BestRound meshRounds(const Surface& surf, const RemeshOptions& opt, const Progress& progress, Meshing& m,
                     ExemptCorners& exempt, RemeshReport& rep, StageClock& clock, const RepairLeft& repairLeft) {
  Patches& work = m.patches;
  BestRound best;
  MeshBuffers out;
  std::vector<uint32_t> triPatch, vertexFace;
  bool outIsBest = false;  // the best round is the current one: kept in out (moved, not copied)
  size_t bestBad = SIZE_MAX, bestCollapsed = SIZE_MAX, bestDoubled = SIZE_MAX;  // bestDoubled: stitch defects
  int staleRounds = 0;  // certificate rounds in a row without progress (see kRoundProgress)
  std::vector<std::vector<uint32_t>> bestCurveSamples;
  // repairLeft on a copy of the current round (its curve samples and exempt wedges are current)
  const auto repairLeftOnRound = [&](size_t bad) {
    BestRound trial;
    trial.out = out;
    trial.triPatch = triPatch;
    trial.vertexFace = vertexFace;
    trial.bad = bad;
    return repairLeft(trial);
  };
  for (int cert = 0;; ++cert) {
    // the first round runs the stages in their order; a later one re-meshes what the certificate
    // asked for, its progress that of the certificate's rounds
    const auto report = [&](Stage s, double f) {
      if (cert == 0) progress.check(s, f);
      else progress.check(Stage::Certificate, double(cert) / double(opt.maxCertificateRounds + 1));
    };
    clock.enter(Stage::Refine);
    StageSeconds busy;  // the seconds the patches' refinements and lifts took, over the threads
    // Refine every patch that needs it; a refinement that splits a boundary segment adds a
    // curve sample there, which the patches on the other side of that curve must include: they
    // are refined again from scratch with it, until no patch splits a segment (samples only get
    // added, and each refinement is Ruppert's on its own, so this settles in a few rounds).
    int round = 0;
    for (;; ++round) {
      std::vector<uint32_t> todo;
      for (uint32_t p = 0; p < work.size(); ++p)
        if (work[p]->needsMesh || (work[p]->dirty && round < kConformingRounds)) todo.push_back(p);
      if (todo.empty()) break;
      std::vector<uint8_t> split(todo.size());
      for (size_t i = 0; i < todo.size(); ++i) split[i] = !work[todo[i]]->keepBoundary;
      size_t meshed = 0;
      meshPatches(
          surf, opt, m, todo, split, [](uint32_t) { return true; },
          [&](size_t i) {
            meshed = i + 1;
            report(Stage::Refine, double(meshed) / double(todo.size()));
          },
          [&] { report(Stage::Refine, double(meshed) / double(todo.size())); }, busy);
    }
    // past the round cap (refinements near small angles between curves can keep splitting
    // each other's segments): refine the patches still missing samples once more, without
    // splitting their boundary, so every patch has exactly the curve samples and they stitch
    std::vector<uint32_t> all(work.size());
    for (uint32_t p = 0; p < work.size(); ++p) all[p] = p;
    meshPatches(
        surf, opt, m, all, std::vector<uint8_t>(work.size(), 0), [&](uint32_t p) { return work[p]->dirty; },
        [&](size_t p) {
          rep.warnings.push_back("patch " + std::to_string(p) + ": refined without boundary splits after " +
                                 std::to_string(kConformingRounds) + " conforming rounds");
        },
        [&] { report(Stage::Refine, 1.0); }, busy);
    // refine and lift ran side by side on the threads: the section's time split between them
    clock.split(busy);
    clock.enter(Stage::Optimize);
    report(Stage::Optimize, 0);
    std::vector<std::vector<uint8_t>> active(work.size());
    std::vector<uint8_t> optimize(work.size());
    for (uint32_t p = 0; p < work.size(); ++p) optimize[p] = !work[p]->optimized;
    optimizePatches(surf, opt, m, optimize, active,
                    [&](size_t i, size_t n) { report(Stage::Optimize, double(i) / double(n)); }, rep);
    // curve samples slide along their curves, then the interior around each slid sample gets
    // another optimization (local: the vertices of its stars first), guarded so that it does not
    // take the output farther from the input
    if (opt.optimize && opt.optimizeIterations > 0) {
      active = slideSamples(surf, opt, m, rep);
      for (uint32_t p = 0; p < work.size(); ++p) optimize[p] = !active[p].empty();
      optimizePatches(surf, opt, m, optimize, active, [&](size_t, size_t) { report(Stage::Optimize, 1.0); }, rep);
    }
    rep.conformingRounds = std::max(rep.conformingRounds, round);
    clock.enter(Stage::Stitch);
    report(Stage::Stitch, 0);
    if (outIsBest) {
      best.out = std::move(out);
      best.triPatch = std::move(triPatch);
      best.vertexFace = std::move(vertexFace);
      outIsBest = false;
    }
    out = stitch(surf, m, triPatch, vertexFace);
    clock.enter(Stage::Certificate);
    report(Stage::Certificate, 0);
    if (exempt.vertex.empty()) exempt.find(surf, m, out.vertexCount(), rep);
    exempt.vertex.resize(out.vertexCount(), 0);
    exempt.indexWedges(surf, m.samples);
    // A round never wins by trading bad triangles for collapsed ones, and a stitch defect (the
    // surface is not manifold there) is worse than any angle: a round with fewer always wins.
    const Verdict verdict = judge(out, triPatch, exempt, unsigned(opt.threads));
    const size_t defects = verdict.defects();
    const bool better = defects < bestDoubled ||
                        (defects == bestDoubled && (verdict.collapsed < bestCollapsed || (verdict.collapsed == bestCollapsed && verdict.bad < bestBad)));
    // progress: a stitch defect or a collapsed triangle fewer than the best, or the bad ones down
    // to kRoundProgress of the best's; a best round short of that counts as stale too
    const bool progress = better && (defects < bestDoubled || verdict.collapsed < bestCollapsed ||
                                     double(verdict.bad) < kRoundProgress * double(bestBad));
    const bool tie = !better && defects == bestDoubled && verdict.collapsed == bestCollapsed && verdict.bad == bestBad;
    // The repair, tried on a copy of every round at least as good as the best (a tie's bad
    // triangles are other ones, which it may take): where it takes them all, the round is the
    // best and the last. A round of smaller triangles for what the repair takes is triangles and
    // time for nothing (a trial costs a few percent of a round: 0.012 s against about 0.5 s for
    // a round of ChineseDragon-10kv at 35°), and a round often trades its bad triangles for others
    // near the same spot (ChineseDragon-10kv at 35°: one at 32.2° with two curve samples, then one
    // at 34.97° with one, which the repair lifts; docs/decisions/0052).
    const bool repaired = defects == 0 && verdict.bad > 0 && repairLeft && (better || tie) && repairLeftOnRound(verdict.bad) == 0;
    if (better || (tie && repaired)) {
      bestDoubled = defects;
      bestBad = verdict.bad;
      bestCollapsed = verdict.collapsed;
      outIsBest = true;
      bestCurveSamples = m.samples.cm.curveSamples;
      if (opt.patches) best.patches = patchSnapshot(m, out);
    }
    if (repaired) break;
    staleRounds = progress ? 0 : staleRounds + 1;
    // Two rounds in a row without progress: what is left does not yield to size (a corner whose
    // planar and 3D angles differ, a cut meeting a curve at a small angle), and the repair takes
    // the rest. A single round without it is no reason to stop: the spots accumulate, and the
    // next round often gets there (docs/decisions/0008). While the best round still has a stitch
    // defect the rounds go on to their cap: a non-manifold output is an error, worse than any
    // angle.
    // ... but only when the repair does take the rest (tried above on the best round when it
    // was made): otherwise the rounds go on to their cap (ChineseDragon-10kv at 35°: after two
    // stale rounds the repair left a cut sample's corner at 30°; four more rounds and the repair
    // left none; docs/decisions/0042).
    if (staleRounds >= 2 && bestDoubled == 0 && (bestBad == 0 || !repairLeft)) break;
    // a stitch defect left at the cap gets kKeepBoundaryRounds more, its patches keeping their
    // boundary (PatchWork::keepBoundary): a non-manifold output is an error
    const int rounds = opt.maxCertificateRounds + (bestDoubled > 0 ? kKeepBoundaryRounds : 0);
    if ((verdict.bad == 0 && defects == 0) || cert >= rounds) break;
    // 3D angle certificate: where a lifted triangle is below the bound, ask for smaller planar
    // triangles there and re-mesh the patch.
    requestRefinement(verdict, out, triPatch, exempt, cert >= opt.maxCertificateRounds, work);
    ++rep.certificateRounds;
  }
  if (outIsBest) {
    best.out = std::move(out);
    best.triPatch = std::move(triPatch);
    best.vertexFace = std::move(vertexFace);
  }
  best.bad = bestBad;
  // sized for the last round; the best one may have more vertices (only curve samples, the
  // first vertices of every round, can be exempt)
  exempt.vertex.resize(best.out.vertexCount(), 0);
  m.samples.cm.curveSamples = std::move(bestCurveSamples);
  exempt.indexWedges(surf, m.samples);  // the best round's curves: the repair asks which corner owns a triangle
  progress.check(Stage::Certificate, 1.0);
  return best;
}

}  // namespace conformesh::pipeline
