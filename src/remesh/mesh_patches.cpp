#include "remesh/mesh_patches.h"

#include <exception>

#include "core/parallel_for.h"

namespace conformesh::pipeline {
namespace {

// A meshing made ahead of its turn, or the error making it threw (thrown at its turn, if it is
// still the meshing the patch gets then).
struct Ahead {
  bool made = false;
  PatchMeshing r;
  std::exception_ptr error;
};

bool sameBoundary(const std::vector<BoundaryPoint>& a, const std::vector<BoundaryPoint>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].sample != b[i].sample || a[i].loopPos != b[i].loopPos || a[i].param != b[i].param || a[i].x != b[i].x ||
        a[i].y != b[i].y || a[i].inner != b[i].inner)
      return false;
  return true;
}

// The triangles a meshing of the patch makes, roughly: its area over its target size squared
// (only to give the threads the largest patches first).
double meshingCost(const Surface& surf, const PatchWork& w) {
  double c = 0;
  for (size_t f = 0; f < w.pm.faceInput.size(); ++f) {
    const uint32_t* t = &w.pm.mesh.triangles[3 * f];
    const double h = (w.hSub[t[0]] + w.hSub[t[1]] + w.hSub[t[2]]) / 3;
    c += surf.g.faceArea(w.pm.faceInput[f]) / (h * h);
  }
  return c;
}

}  // namespace

void meshPatches(const Surface& surf, const RemeshOptions& opt, Meshing& m, const std::vector<uint32_t>& todo,
                 const std::vector<uint8_t>& splitSegments, const std::function<bool(uint32_t)>& wanted,
                 const std::function<void(size_t)>& meshed, const std::function<void()>& waiting, StageSeconds& busy) {
  std::vector<Ahead> ahead(todo.size());
  // make the meshings of items `items` apart, on the threads (nothing shared is written meanwhile)
  const auto makeAhead = [&](const std::vector<size_t>& items) {
    std::vector<double> cost(items.size());
    for (size_t k = 0; k < items.size(); ++k) cost[k] = meshingCost(surf, *m.patches[todo[items[k]]]);
    const std::vector<size_t> byCost = largestFirst(cost);
    parallelFor(
        items.size(), unsigned(opt.threads),
        [&](size_t k) {
          const size_t i = items[byCost[k]];
          Ahead& a = ahead[i];
          // a meshing made again: the seconds of the one it replaces count as well
          const double refined = a.r.refineSeconds, lifted = a.r.liftSeconds;
          a = Ahead{};
          a.made = true;
          try {
            a.r = refineApart(surf, opt, m, todo[i], splitSegments[i]);
            a.r.refineSeconds += refined;
            a.r.liftSeconds += lifted;
          } catch (...) {
            a.error = std::current_exception();
            a.r.bp = boundaryPoints(surf, m.samples, *m.patches[todo[i]]);
          }
        },
        [&](size_t) {
          if (waiting) waiting();
        });
  };
  // still the meshing the patch gets now: its boundary points are the same
  const auto current = [&](size_t k) {
    return sameBoundary(ahead[k].r.bp, boundaryPoints(surf, m.samples, *m.patches[todo[k]]));
  };
  std::vector<size_t> first;
  for (size_t k = 0; k < todo.size(); ++k)
    if (wanted(todo[k])) first.push_back(k);
  // one thread: no meshing ahead (meshPatch at each turn is the same, without the copies)
  const bool parallel = resolveThreads(unsigned(opt.threads)) > 1 && first.size() > 1;
  if (parallel) makeAhead(first);
  for (size_t k = 0; k < todo.size(); ++k) {
    const uint32_t p = todo[k];
    if (!wanted(p)) {
      ahead[k] = Ahead{};
      continue;
    }
    if (parallel && ahead[k].made && !current(k)) {
      // samples were added on its boundary since: made again, with every later meshing in the
      // same case, from the samples as they are now
      std::vector<size_t> again = {k};
      for (size_t j = k + 1; j < todo.size(); ++j)
        if (ahead[j].made && !current(j)) again.push_back(j);
      makeAhead(again);
    }
    Ahead a = std::move(ahead[k]);
    ahead[k] = Ahead{};
    if (a.made && a.error) std::rethrow_exception(a.error);
    if (a.made && !a.r.needsRepair) {
      commitMeshing(surf, m, p, a.r, busy);
    } else {
      busy.refine += a.r.refineSeconds;  // a refinement whose chords crossed
      meshPatch(surf, opt, m, p, busy, splitSegments[k]);
    }
    meshed(k);
  }
}

}  // namespace conformesh::pipeline
