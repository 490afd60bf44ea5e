#include "remesh/rounds.h"

#include <algorithm>
#include <string>

#include "remesh/mesh_patch.h"
#include "remesh/slide_samples.h"
#include "remesh/stitch.h"

namespace conformesh::pipeline {
namespace {

// Rounds of re-refining patches whose boundary got samples from a neighbour's segment splits.
constexpr int kConformingRounds = 8;
// Certificate rounds past the cap for a stitch defect still there, with its patches keeping their
// boundary (one opened it in every case measured; the second is a margin).
constexpr int kKeepBoundaryRounds = 2;

}  // namespace

BestRound meshRounds(const Surface& surf, const RemeshOptions& opt, const Progress& progress, Meshing& m,
                     ExemptCorners& exempt, RemeshReport& rep, std::chrono::steady_clock::time_point& clock) {
  Patches& work = m.patches;
  BestRound best;
  MeshBuffers out;
  std::vector<uint32_t> triPatch, vertexFace;
  bool outIsBest = false;  // the best round is the current one: kept in out (moved, not copied)
  size_t bestBad = SIZE_MAX, bestCollapsed = SIZE_MAX, bestDoubled = SIZE_MAX;  // bestDoubled: stitch defects
  int staleRounds = 0;  // certificate rounds in a row that did not beat the best
  std::vector<std::vector<uint32_t>> bestCurveSamples;
  for (int cert = 0;; ++cert) {
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
      for (size_t i = 0; i < todo.size(); ++i) {
        meshPatch(surf, opt, m, todo[i], !work[todo[i]]->keepBoundary);
        progress.check(Stage::Refine, double(i + 1) / double(todo.size()));
      }
    }
    // past the round cap (refinements near small angles between curves can keep splitting
    // each other's segments): refine the patches still missing samples once more, without
    // splitting their boundary, so every patch has exactly the curve samples and they stitch
    for (uint32_t p = 0; p < work.size(); ++p)
      if (work[p]->dirty) {
        meshPatch(surf, opt, m, p, false);
        rep.warnings.push_back("patch " + std::to_string(p) + ": refined without boundary splits after " +
                               std::to_string(kConformingRounds) + " conforming rounds");
      }
    for (uint32_t p = 0; p < work.size(); ++p)
      if (!work[p]->optimized) {
        optimizeMesh(surf, opt, m, p, rep);
        progress.check(Stage::Refine, 1.0);
      }
    // curve samples slide along their curves, then the interior around each slid sample gets
    // another optimization (local: the vertices of its stars first), guarded so that it does not
    // take the output farther from the input
    if (opt.optimize && opt.optimizeIterations > 0) {
      const std::vector<std::vector<uint8_t>> slid = slideSamples(surf, opt, m, rep);
      for (uint32_t p = 0; p < work.size(); ++p)
        if (!slid[p].empty()) {
          optimizeMesh(surf, opt, m, p, rep, slid[p]);
          progress.check(Stage::Refine, 1.0);
        }
    }
    rep.conformingRounds = std::max(rep.conformingRounds, round);
    rep.seconds.refine += elapsed(clock);
    if (outIsBest) {
      best.out = std::move(out);
      best.triPatch = std::move(triPatch);
      best.vertexFace = std::move(vertexFace);
      outIsBest = false;
    }
    out = stitch(surf, m, triPatch, vertexFace);
    if (exempt.vertex.empty()) exempt.find(surf, m, out.vertexCount(), rep);
    exempt.vertex.resize(out.vertexCount(), 0);
    exempt.indexWedges(surf, m.samples);
    // A round never wins by trading bad triangles for collapsed ones, and a stitch defect (the
    // surface is not manifold there) is worse than any angle: a round with fewer always wins.
    const Verdict verdict = judge(out, triPatch, exempt);
    const size_t defects = verdict.defects();
    if (defects < bestDoubled ||
        (defects == bestDoubled && (verdict.collapsed < bestCollapsed || (verdict.collapsed == bestCollapsed && verdict.bad < bestBad)))) {
      bestDoubled = defects;
      bestBad = verdict.bad;
      bestCollapsed = verdict.collapsed;
      outIsBest = true;
      bestCurveSamples = m.samples.cm.curveSamples;
      if (opt.returnPatches) best.patches = patchSnapshot(m, out);
      staleRounds = 0;
    } else if (++staleRounds >= 2 && bestDoubled == 0) {
      // Two rounds in a row no better than the best: what is left does not yield to size (a
      // corner whose planar and 3D angles differ, a cut meeting a curve at a small angle). A
      // single round that is not better is no reason to stop: the spots accumulate, and the
      // next round often gets there (docs/decisions/0008). While the
      // best round still has a stitch defect the rounds go on to their cap: a non-manifold
      // output is an error, worse than any angle.
      break;
    }
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
  return best;
}

}  // namespace conformesh::pipeline
