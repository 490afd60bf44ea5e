// conformesh — the certificate's spots as a size field: min over spots of h + |x − p| / 2.
//
// Every certificate round adds a spot (planar point p, size h) at each lifted triangle below the
// angle bound; the patch's refinement then asks for the size at every triangle it checks. A scan
// of all spots per query is quadratic once a patch has thousands; this bins them in a uniform
// grid and visits rings of cells outward until no farther spot can be smaller. The result is the
// same minimum as the scan (each term is computed the same way, and min does not depend on order).
#pragma once

#include <cstdint>
#include <vector>

namespace conformesh {

struct Spot {
  double x, y, h;
};

class SpotField {
 public:
  SpotField() = default;
  explicit SpotField(const std::vector<Spot>& spots);
  //! min(bound, min over spots of h + hypot(x − spot.x, y − spot.y) / 2).
  double size(double x, double y, double bound) const;
  bool empty() const { return spots_.empty(); }

 private:
  std::vector<Spot> spots_;       // by cell
  std::vector<uint32_t> start_;   // per cell (row-major), then one past the last
  double x0_ = 0, y0_ = 0, cell_ = 1, hMin_ = 0;
  int nx_ = 0, ny_ = 0;
};

}  // namespace conformesh
