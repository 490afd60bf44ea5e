#include "remesh/spot_field.h"

#include <algorithm>
#include <cmath>

#include "core/detmath.h"

namespace conformesh {

SpotField::SpotField(const std::vector<Spot>& spots) {
  if (spots.empty()) return;
  double x1 = spots[0].x, y1 = spots[0].y;
  x0_ = x1, y0_ = y1, hMin_ = spots[0].h;
  for (const Spot& s : spots) {
    x0_ = std::min(x0_, s.x), y0_ = std::min(y0_, s.y);
    x1 = std::max(x1, s.x), y1 = std::max(y1, s.y);
    hMin_ = std::min(hMin_, s.h);
  }
  // about two spots per cell over the spots' bounding box, at most 1024 cells a side
  const double w = x1 - x0_, hgt = y1 - y0_;
  const double area = std::max(w * hgt, 1e-300);
  cell_ = std::sqrt(2.0 * area / double(spots.size()));
  cell_ = std::max({cell_, w / 1024.0, hgt / 1024.0});
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = std::max({w, hgt, 1.0});
  nx_ = std::max(1, int(w / cell_) + 1);
  ny_ = std::max(1, int(hgt / cell_) + 1);
  std::vector<uint32_t> cellOf(spots.size());
  start_.assign(size_t(nx_) * size_t(ny_) + 1, 0);
  for (size_t i = 0; i < spots.size(); ++i) {
    const int cx = std::min(nx_ - 1, int((spots[i].x - x0_) / cell_));
    const int cy = std::min(ny_ - 1, int((spots[i].y - y0_) / cell_));
    cellOf[i] = uint32_t(cy) * uint32_t(nx_) + uint32_t(cx);
    ++start_[cellOf[i] + 1];
  }
  for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  spots_.resize(spots.size());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < spots.size(); ++i) spots_[fill[cellOf[i]]++] = spots[i];
}

double SpotField::size(double x, double y, double bound) const {
  double best = bound;
  auto visit = [&](size_t c) {
    for (uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
      const Spot& s = spots_[i];
      best = std::min(best, s.h + 0.5 * dmath::hypot(x - s.x, y - s.y));
    }
  };
  if (spots_.empty()) return best;
  // the cell of the query's nearest point in the grid's box: projecting onto a convex box
  // shortens no distance to a point in it, so the ring bounds below hold from there too
  const double fx = std::floor((x - x0_) / cell_), fy = std::floor((y - y0_) / cell_);
  if (std::isnan(fx) || std::isnan(fy)) return best;
  const long qx = long(std::clamp(fx, 0.0, double(nx_ - 1))), qy = long(std::clamp(fy, 0.0, double(ny_ - 1)));
  const long far = std::max({qx, nx_ - 1 - qx, qy, ny_ - 1 - qy});  // rings to cover the grid
  for (long k = 0; k <= far; ++k) {
    // every cell of ring k is at least k − 1 cells from the query (half a cell of slack for
    // spots that rounding put in a neighbouring cell)
    if (k >= 2 && hMin_ + 0.5 * (double(k) - 1.5) * cell_ >= best) break;
    const long xlo = std::max(qx - k, 0L), xhi = std::min(qx + k, long(nx_) - 1);
    const long ylo = std::max(qy - k, 0L), yhi = std::min(qy + k, long(ny_) - 1);
    for (long cy = ylo; cy <= yhi; ++cy) {
      const size_t row = size_t(cy) * size_t(nx_);
      if (cy == qy - k || cy == qy + k) {
        for (long cx = xlo; cx <= xhi; ++cx) visit(row + size_t(cx));
      } else {
        if (qx - k >= 0) visit(row + size_t(qx - k));
        if (k > 0 && qx + k < nx_) visit(row + size_t(qx + k));
      }
    }
  }
  return best;
}

}  // namespace conformesh
