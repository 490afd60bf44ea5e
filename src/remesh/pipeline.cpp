#include "remesh/pipeline.h"

#include <algorithm>

namespace conformesh::pipeline {

void Progress::check(Stage s, double f) const {
  if (fn && !fn(s, std::clamp(f, 0.0, 1.0))) fail(Code::Cancelled, s, "cancelled by the progress callback");
}

double elapsed(std::chrono::steady_clock::time_point& t) {
  auto now = std::chrono::steady_clock::now();
  double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

}  // namespace conformesh::pipeline
