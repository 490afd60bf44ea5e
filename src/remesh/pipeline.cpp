#include "remesh/pipeline.h"

#include <algorithm>

namespace conformesh::pipeline {

void Progress::check(Stage s, double f) const {
  if (fn && !fn(s, std::clamp(f, 0.0, 1.0))) fail(Code::Cancelled, s, "cancelled by the progress callback");
}

StageClock::StageClock(Stage first) : current_(first), start_(Clock::now()), last_(start_) {}

Stage StageClock::enter(Stage s) {
  const Clock::time_point now = Clock::now();
  if (double* t = seconds_.of(current_)) *t += std::chrono::duration<double>(now - last_).count();
  last_ = now;
  const Stage left = current_;
  current_ = s;
  return left;
}

StageSeconds StageClock::seconds() {
  enter(current_);
  StageSeconds s = seconds_;
  s.total = std::chrono::duration<double>(last_ - start_).count();
  return s;
}

}  // namespace conformesh::pipeline
