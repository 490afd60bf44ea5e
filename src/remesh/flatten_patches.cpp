#include "remesh/flatten_patches.h"
#include "core/constants.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace conformesh::pipeline {
namespace {

// Patches with fewer input faces are not split further. A single triangle always develops
// isometrically, so splitting down to small patches beats the round-disk fallback, whose
// distortion on a small curved patch leaves triangles below the bound (docs/decisions/0009).
constexpr size_t kMinSplitFaces = 2;

// The 3D angle sum at each vertex of a patch over the patch's faces.
std::vector<double> cornerWedgeAngles(const F::PatchMesh& pm) {
  std::vector<double> a(pm.vertexInput.size(), 0.0);
  const auto& P = pm.mesh.positions;
  for (size_t f = 0; f < pm.faceInput.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      uint32_t v[3] = {pm.mesh.triangles[3 * f + c], pm.mesh.triangles[3 * f + (c + 1) % 3],
                       pm.mesh.triangles[3 * f + (c + 2) % 3]};
      F::Vec3 p0{P[3 * v[0]], P[3 * v[0] + 1], P[3 * v[0] + 2]};
      F::Vec3 p1{P[3 * v[1]], P[3 * v[1] + 1], P[3 * v[1] + 2]};
      F::Vec3 p2{P[3 * v[2]], P[3 * v[2] + 1], P[3 * v[2] + 2]};
      a[v[0]] += F::angleBetween(p1 - p0, p2 - p0);
    }
  return a;
}

// Corners for the corner-preserving boundary condition (the fallback when the free boundary
// overlaps itself): boundary wedges at curve corners whose 3D angle differs from π by more than
// 10°, each with its own 3D angle as target; the flow spreads the rest of the boundary turning
// (2π − Σ(π − α)) along the sides by arc length, so the sides bend instead of the corners.
std::vector<std::pair<uint32_t, double>> boundaryCorners(const F::Segmentation& seg, const F::PatchMesh& pm) {
  std::vector<double> angle = cornerWedgeAngles(pm);
  std::vector<uint8_t> onBoundary(pm.vertexInput.size(), 0);
  for (const auto& h : pm.boundaryLoops[0]) onBoundary[pm.mesh.triangles[3 * h.face + h.corner]] = 1;
  std::vector<std::pair<uint32_t, double>> out;
  for (uint32_t v = 0; v < pm.vertexInput.size(); ++v) {
    if (!onBoundary[v] || !seg.vertexCorner[pm.vertexInput[v]]) continue;
    if (std::abs(angle[v] - kPi) < 10.0 * kPi / 180.0) continue;
    out.push_back({v, std::clamp(angle[v], 1e-3, 2 * kPi - 1e-3)});
  }
  return out;
}

}  // namespace

Patches flattenPatches(Surface& surf, const RemeshOptions& opt, const Progress& progress, RemeshReport& rep) {
  // flattened patches by their exact face set: splitting a patch can reroute the cuts of its
  // neighbours (improveCutJunctions), which changes their faces and so their flattening
  std::map<std::vector<uint32_t>, std::unique_ptr<PatchWork>> cache;
  auto keyOf = [](std::vector<uint32_t> faces) {
    std::sort(faces.begin(), faces.end());
    return faces;
  };
  // each round flattens what is new and splits at most one patch: the rounds are capped by the
  // patches the segmentation may make (a split that undoes another would otherwise cycle)
  const uint32_t maxPatches = F::FeatureOptions{}.maxPatches;
  for (int round = 0;; ++round) {
    if (round > 64 + 2 * int(maxPatches) || surf.seg.patches.size() > maxPatches)
      fail(Code::IterationLimit, Stage::Flatten,
           "splitting patches for their scale factor did not settle (" + std::to_string(surf.seg.patches.size()) + " patches after " +
               std::to_string(round) + " rounds)");
    auto mask = surf.seg.curveMask();
    bool split = false;
    for (uint32_t p = 0; p < surf.seg.patches.size() && !split; ++p) {
      const auto& faces = surf.seg.patches[p];
      auto key = keyOf(faces);
      if (cache.count(key)) continue;
      auto w = std::make_unique<PatchWork>();
      w->pm = F::extractPatch(surf.g, mask, faces);
      if (!w->pm.isDisk()) fail(Code::InternalError, Stage::Flatten, "a patch is not a disk after cutting");
      // Boundary conditions, least distorting first. Free (u = 0 on the boundary): isometric
      // on developable patches, so planar angles are 3D angles and corners keep theirs; its
      // layout can overlap itself on strongly curved patches. Then corner-preserving (corners
      // keep their 3D angle, the sides bend), then the round disk (always embedded).
      std::vector<BoundaryCondition> order = {opt.boundary};
      for (BoundaryCondition bc : {BoundaryCondition::Free, BoundaryCondition::Corners, BoundaryCondition::Circle})
        if (bc != opt.boundary) order.push_back(bc);
      bool flattened = false;
      std::string lastError;
      for (BoundaryCondition bc : order) {
        FlattenOptions fo;
        fo.boundary = bc;
        if (bc == BoundaryCondition::Corners) {
          fo.corners = boundaryCorners(surf.seg, w->pm);
          if (fo.corners.empty()) continue;
        }
        try {
          w->flat = flatten(w->pm.mesh, fo);
          flattened = true;
          if (bc != order.front())
            rep.warnings.push_back(std::string("patch flattened with the ") +
                                    (bc == BoundaryCondition::Free      ? "free"
                                     : bc == BoundaryCondition::Corners ? "corner-preserving"
                                                                        : "round (circle)") +
                                    " boundary condition after: " + lastError + " [patch of " + std::to_string(faces.size()) + " faces]");
          break;
        } catch (const Error& e) {
          if (e.code() == Code::Cancelled) throw;
          lastError = e.what();
          // the free boundary failed (its layout overlaps itself): smaller parts are closer to
          // developable and keep the least distorting map; split while the patch is big enough
          if (bc == order.front() && faces.size() >= kMinSplitFaces && F::splitPatch(surf.g, surf.seg, p)) {
            ++rep.patchSplitsForScale;
            rep.warnings.push_back("patch split after its first boundary condition failed: " + lastError);
            split = true;
            break;
          }
        }
      }
      if (split) break;
      if (!flattened) {
        // every boundary condition failed (a layout that overlaps itself or a flow that stalls):
        // split the patch and retry
        if (faces.size() < kMinSplitFaces || !F::splitPatch(surf.g, surf.seg, p))
          fail(Code::NumericalFailure, Stage::Flatten, "patch " + std::to_string(p) + " could not be flattened: " + lastError);
        ++rep.patchSplitsForScale;
        rep.warnings.push_back("patch split after a flattening failure: " + lastError);
        split = true;
        break;
      }
      // planar/3D scale per sub vertex from the areas of the input faces around it
      const size_t nv = w->pm.vertexInput.size();
      std::vector<double> a2(nv, 0.0), a3(nv, 0.0);
      const auto& uv = w->flat.uv;
      for (size_t f = 0; f < w->pm.faceInput.size(); ++f) {
        const uint32_t* t = &w->pm.mesh.triangles[3 * f];
        double ax = uv[2 * t[1]] - uv[2 * t[0]], ay = uv[2 * t[1] + 1] - uv[2 * t[0] + 1];
        double bx = uv[2 * t[2]] - uv[2 * t[0]], by = uv[2 * t[2] + 1] - uv[2 * t[0] + 1];
        double area2 = std::abs(ax * by - ay * bx) * 0.5, area3 = surf.g.faceArea(w->pm.faceInput[f]);
        for (int c = 0; c < 3; ++c) a2[t[c]] += area2, a3[t[c]] += area3;
      }
      w->scaleSub.resize(nv);
      w->hSub.resize(nv);
      double smin = INFINITY, smax = 0;
      for (size_t v = 0; v < nv; ++v) {
        w->scaleSub[v] = a3[v] > 0 ? std::sqrt(a2[v] / a3[v]) : 1.0;
        w->hSub[v] = surf.sizing.h[w->pm.vertexInput[v]];
        smin = std::min(smin, w->scaleSub[v]);
        smax = std::max(smax, w->scaleSub[v]);
      }
      if (smax > opt.maxScaleRatio * smin && faces.size() >= kMinSplitFaces) {
        if (F::splitPatch(surf.g, surf.seg, p)) {
          ++rep.patchSplitsForScale;
          split = true;
          break;
        }
      }
      cache.emplace(key, std::move(w));
      progress.check(Stage::Flatten, double(cache.size()) / double(surf.seg.patches.size() + 1));
    }
    if (split) continue;
    Patches work;
    for (const auto& faces : surf.seg.patches) work.push_back(std::move(cache.at(keyOf(faces))));
    return work;
  }
}

}  // namespace conformesh::pipeline
