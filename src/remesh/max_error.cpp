#include "remesh/max_error.h"

#include <algorithm>
#include <cmath>
#include <string>

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
  bool coneTips = options.coneTips;
  double withoutConeTips = INFINITY;  // the distance of the attempt before the cone tips were tried (∞: not tried)
  for (int a = 0; a < kMaxAttempts; ++a) {
    RemeshOptions o = options;
    o.chordTolerance = factor * bound;
    o.coneTips = coneTips;
    o.computeHausdorff = true;
    RemeshResult r = attempt(o);
    if (!r.status.ok()) return r;
    const double distance = r.report.hausdorffRel * diagonal;
    attempts.push_back({o.chordTolerance, distance});
    notes.push_back("max error: attempt " + std::to_string(a + 1) + " (chord tolerance " + number(o.chordTolerance) + (o.coneTips ? ", cone tips" : "") +
                    "): Hausdorff distance " + number(distance) + ", bound " + number(bound) + ", " +
                    std::to_string(r.report.triangles) + " triangles");
    if (distance <= kAcceptFraction * bound) {
      if (lo == 0 || r.report.triangles < best.report.triangles) best = std::move(r);
      lo = std::max(lo, factor);
      // close enough, or no distance to scale by (the output lies on the input)
      if (distance >= kCloseEnoughFraction * bound || !(distance > 0)) break;
    } else if (!o.coneTips && withoutConeTips == INFINITY) {
      // above the bound: first where the curvature bound is blind (a cone's tip the output cuts
      // off in proportion to its size: features/sizing.h), at the same tolerance; the tolerance
      // is tightened everywhere only when that is not enough (docs/decisions/0049).
      coneTips = true;
      withoutConeTips = distance;
      continue;
    } else {
      // the cone tips' sizes did not lower the distance: its excess is elsewhere (stanford-bunny)
      if (o.coneTips && !options.coneTips && distance >= withoutConeTips) coneTips = false;
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
