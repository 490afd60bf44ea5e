#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/detmath.h"
#include "remesh/spot_field.h"

using namespace conformesh;

namespace {
double scan(const std::vector<Spot>& spots, double x, double y, double bound) {
  double best = bound;
  for (const Spot& s : spots) best = std::min(best, s.h + 0.5 * dmath::hypot(x - s.x, y - s.y));
  return best;
}
}  // namespace

TEST_CASE("spot field: the same minimum as a scan of every spot, inside and outside the spots' box") {
  std::mt19937 rng(7);
  for (int layout = 0; layout < 3; ++layout) {
    std::uniform_real_distribution<double> ux(0.0, layout == 2 ? 1e-3 : 10.0), uy(0.0, layout == 1 ? 0.0 : 3.0);
    std::uniform_real_distribution<double> uh(1e-4, 0.5);
    std::vector<Spot> spots;
    const int n = layout == 0 ? 2000 : 300;
    for (int i = 0; i < n; ++i) spots.push_back({ux(rng), uy(rng), uh(rng)});
    if (layout == 0) spots.push_back(spots.back());  // a repeated spot
    const SpotField field(spots);
    std::uniform_real_distribution<double> qx(-5.0, 15.0), qy(-2.0, 5.0), qb(0.0, 3.0);
    for (int q = 0; q < 3000; ++q) {
      const double x = qx(rng), y = qy(rng), bound = q % 10 == 0 ? double(INFINITY) : qb(rng);
      CHECK(field.size(x, y, bound) == scan(spots, x, y, bound));  // exact: the same terms
    }
  }
  const SpotField none{std::vector<Spot>{}};
  CHECK(none.size(1, 2, 3.5) == 3.5);
}
