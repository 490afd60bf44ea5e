#include "remesh/max_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/vec3.h"
#include "mesh/io_detail.h"
#include "quality/metrics.h"

namespace conformesh {
namespace {

// The first chord tolerance, as a fraction of the bound: the curvature sizing bounds the chord
// error of an arc by the tolerance, but the Hausdorff distance also has the triangles' longest
// edges above the size, the gradation and the input's own facets (1.3 to 2.4 times the
// tolerance on the models of ../shared/data), so 0.4 lands near the bound at the first attempt.
constexpr double kFirstToleranceFactor = 0.4;
// Attempts at most (each a whole remesh); the chord error grows about linearly with the
// tolerance, so each attempt rescales it by the bound over the measured distance.
constexpr int kMaxAttempts = 4;
// The sampled distance is a lower bound of the true one: an attempt counts as within the bound
// when its measured distance is at most this fraction of it.
constexpr double kAcceptFraction = 0.9;
// An attempt within the bound whose distance is above this fraction of it is close enough: a
// looser tolerance would gain little.
constexpr double kCloseEnoughFraction = 0.6;
// The largest step of the tolerance from one attempt to the next: a distance far below the bound
// (a flat surface: about 0) would otherwise ask for an unbounded tolerance, attempt after attempt.
constexpr double kMaxToleranceStep = 8.0;

// A length in a message: the digits that read back to it, in any locale (std::to_string gives
// six decimals, 0.000000 for a tolerance of 1e-7).
std::string number(double v) {
  if (!std::isfinite(v)) return std::to_string(v);
  std::string s;
  io_detail::appendDouble(s, v);
  return s;
}

// the diagonal the report's hausdorffRel is relative to
double inputDiagonal(const MeshBuffers& m) { return quality::boundingBox(m).diagonal(); }

// A cut that leaves the distance above this fraction of what it was made at did not find what
// keeps it there.
constexpr double kLocalProgress = 0.9;
// An attempt within the bound that leaves a triangle below the angle bound outside the input's
// corners: the next tolerance, this much tighter (any other refines every patch anew).
constexpr double kRetryStep = 0.9;
// Above the bound, the sizes are cut where the attempt's distance exceeds this fraction of it
// (below the acceptance, so the places just under it are not the next attempt's excess) ...
constexpr double kLocalThreshold = 0.75;
// ... to what brings a linear error there to this fraction of the bound (the chord error falls
// with the square of the size: the cut is the larger one a cone's tip needs).
constexpr double kLocalAim = 0.6;

// The sizes an attempt's output asks for where it is too far from the input (absolute lengths per
// input vertex, cut in `local`): each sample of the report's Hausdorff measure (the same points:
// quality::surfaceSamples with its seeds) farther than `threshold` from the other mesh cuts the
// size at the vertices of the input face it lies on or nearest to, to the longest edge of the
// output triangle it lies on or nearest to scaled by target / distance. The sizing's gradation
// spreads each cut; a vertex cut before is cut from its size then, if smaller. Returns the input
// vertices whose size was cut.
size_t cutSizesWhereExceeded(const MeshBuffers& input, const MeshBuffers& output, size_t samples, double threshold, double target,
                             std::vector<double>& local) {
  const quality::TriangleMeshDistance toInput(input), toOutput(output);
  const double limit = threshold * threshold;
  std::vector<uint8_t> cut(input.vertexCount(), 0);
  const auto longestEdge = [&](int64_t t) {
    const auto at = [&](int k) {
      const size_t v = output.triangles[3 * size_t(t) + size_t(k % 3)];
      return Vec3{output.positions[3 * v], output.positions[3 * v + 1], output.positions[3 * v + 2]};
    };
    return std::max({norm(at(1) - at(0)), norm(at(2) - at(1)), norm(at(0) - at(2))});
  };
  const auto cutAt = [&](int64_t inputFace, int64_t outputTriangle, double distanceSquared) {
    if (inputFace < 0 || outputTriangle < 0) return;
    const double scale = target / std::sqrt(distanceSquared), edge = longestEdge(outputTriangle);
    for (int k = 0; k < 3; ++k) {
      // a vertex cut before and still too far: cut again from what it asked for (the output's
      // edges there may be shorter than the error they leave: a spike's tip)
      const uint32_t v = input.triangles[3 * inputFace + k];
      const double size = std::min(edge, local[v]) * scale;
      if (size < local[v]) local[v] = size, cut[v] = 1;
    }
  };
  quality::HausdorffOptions defaults;
  int64_t hint = -1;
  for (const Vec3& p : quality::surfaceSamples(output, samples, defaults.seed)) {  // the output's distance to the input
    const quality::ClosestHit hit = toInput.closest(p, hint, limit);
    hint = hit.primitive;
    if (hit.distanceSquared > limit) cutAt(hit.primitive, toOutput.closest(p).primitive, hit.distanceSquared);
  }
  hint = -1;
  for (const Vec3& p : quality::surfaceSamples(input, samples, defaults.seed + 1)) {  // the input's to the output
    const quality::ClosestHit hit = toOutput.closest(p, hint, limit);
    hint = hit.primitive;
    if (hit.distanceSquared > limit) cutAt(toInput.closest(p).primitive, hit.primitive, hit.distanceSquared);
  }
  return size_t(std::count(cut.begin(), cut.end(), 1));
}

}  // namespace

bool errorDriven(const RemeshOptions& o) { return o.maxError > 0 || (o.maxError < 0 && o.maxErrorRel > 0); }

double maxErrorBound(const MeshBuffers& input, const RemeshOptions& o) {
  return o.maxError > 0 ? o.maxError : o.maxErrorRel * inputDiagonal(input);
}

RemeshResult remeshWithinError(const MeshBuffers& input, const RemeshOptions& options,
                               const std::function<RemeshResult(const RemeshOptions&)>& attempt) {
  const double bound = maxErrorBound(input, options), diagonal = inputDiagonal(input);
  RemeshResult best;
  // the tolerance factors known to be within the bound (lo, with its result in best) and above it
  double lo = 0, hi = INFINITY, factor = kFirstToleranceFactor;
  std::vector<std::string> notes;
  std::vector<std::pair<double, double>> attempts;  // chord tolerance, measured distance
  // per input vertex, the sizes cut where an attempt was too far (∞: none); the caller's own
  // vertexSizing bounds them too
  std::vector<double> local;
  double lastCutFrom = INFINITY;  // the distance the last cut was made at
  bool localStalled = false;      // a cut that did not lower the distance: no more cuts
  for (int a = 0; a < kMaxAttempts; ++a) {
    RemeshOptions o = options;
    o.chordTolerance = factor * bound;
    o.computeHausdorff = true;
    if (!local.empty()) {
      // a value per vertex, finite (prepare.cpp averages two for a vertex it adds)
      o.vertexSizing.resize(input.vertexCount(), diagonal);
      for (size_t v = 0; v < local.size(); ++v) o.vertexSizing[v] = std::min(o.vertexSizing[v], local[v]);
    }
    RemeshResult r = attempt(o);
    if (!r.status.ok()) return r;
    const double distance = r.report.hausdorffRel * diagonal;
    attempts.push_back({o.chordTolerance, distance});
    const size_t cut = local.size() - size_t(std::count(local.begin(), local.end(), INFINITY));
    notes.push_back("max error: attempt " + std::to_string(a + 1) + " (chord tolerance " + number(o.chordTolerance) +
                    (cut > 0 ? ", sizes cut at " + std::to_string(cut) + " input vertices" : "") + "): Hausdorff distance " + number(distance) +
                    ", bound " + number(bound) + ", " + std::to_string(r.report.triangles) + " triangles");
    if (distance <= kAcceptFraction * bound) {
      // within it: the one that holds the angle bound, then the coarsest
      const bool holds = r.report.trianglesBelowBoundOutsideExempt == 0;
      const bool bestHolds = lo > 0 && best.report.trianglesBelowBoundOutsideExempt == 0;
      if (lo == 0 || (holds && !bestHolds) || (holds == bestHolds && r.report.triangles < best.report.triangles)) best = std::move(r);
      lo = std::max(lo, factor);
      if (!holds && !bestHolds) {
        // a triangle the refinement left below the angle bound (a narrow wedge where the
        // conforming rounds ran out): another tolerance refines every patch anew
        factor *= kRetryStep;
        continue;
      }
      // close enough, or no distance to scale by (the output lies on the input)
      if (distance >= kCloseEnoughFraction * bound || !(distance > 0)) break;
    } else {
      // above the bound: the sizes are cut where the distance is exceeded, at the same tolerance
      // (a cone's tip, a facet's bend: a local excess that a tighter tolerance mends only by
      // refining everywhere); the tolerance is tightened when no sample shows where, or when the
      // last cut did not lower the distance (stanford-bunny: 0.240e-3, then 0.239e-3 after a cut
      // at 12 vertices, against 0.225e-3)
      if (distance > kLocalProgress * lastCutFrom) localStalled = true;
      if (local.empty()) local.assign(input.vertexCount(), INFINITY);
      if (!localStalled && cutSizesWhereExceeded(input, r.mesh, o.hausdorffSamples, kLocalThreshold * bound, kLocalAim * bound, local) > 0) {
        lastCutFrom = distance;
        continue;
      }
      hi = std::min(hi, factor);
    }
    // the chord error grows about linearly with the tolerance: aim at the accepted fraction
    // from below, at the middle of the band that ends the search from above (a distance that
    // one spot dominates moves less than the tolerance: aiming at the edge, bunny took four
    // attempts from 0.252e-3 to 0.226e-3 against 0.225e-3), between the factors known to be
    // within and above the bound (geometric mean when that aim falls outside them)
    const double aim = distance <= kAcceptFraction * bound ? kAcceptFraction : 0.5 * (kAcceptFraction + kCloseEnoughFraction);
    factor *= std::min(kMaxToleranceStep, aim * bound / std::max(distance, 1e-300 * bound));
    if (lo > 0 && hi < INFINITY && !(factor > lo && factor < hi)) factor = std::sqrt(lo * hi);
  }
  if (lo == 0) {
    std::string tried;  // each attempt's tolerance and distance, for the caller to judge the bound by
    for (const auto& [tolerance, distance] : attempts)
      tried += std::string(tried.empty() ? "" : "; ") + "tolerance " + number(tolerance) + ": " + number(distance);
    RemeshResult r;
    r.status = Status{Code::IterationLimit, Stage::Report,
                      "the Hausdorff distance " + number(attempts.back().second) + " is above " + std::to_string(int(100 * kAcceptFraction)) + " % of maxError " + number(bound) +
                          " after " + std::to_string(kMaxAttempts) + " attempts with tighter chord tolerances (" + tried + ")"};
    return r;
  }
  best.report.warnings.insert(best.report.warnings.begin(), notes.begin(), notes.end());
  return best;
}

}  // namespace conformesh
