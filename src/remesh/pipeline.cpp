#include "remesh/pipeline.h"

#include <algorithm>

namespace conformesh::pipeline {

void Progress::check(Stage s, double f) const {
  if (fn && !fn(s, std::clamp(f, 0.0, 1.0))) fail(Code::Cancelled, s, "cancelled by the progress callback");
}

StageClock::StageClock(Stage first) : current_(first), start_(Clock::now()), last_(start_) {}

Stage StageClock::enter(Stage s) {
  const Clock::time_point now = Clock::now();
  if (double* t = seconds_.of(current_)) *t += secondsBetween(last_, now);
  last_ = now;
  const Stage left = current_;
  current_ = s;
  return left;
}

void StageClock::split(const StageSeconds& busy) {
  const Clock::time_point now = Clock::now();
  const double wall = secondsBetween(last_, now);
  double sum = 0;
  for (Stage s : kRemeshStages) sum += *busy.of(s);
  if (sum > 0) {
    for (Stage s : kRemeshStages) *seconds_.of(s) += wall * (*busy.of(s) / sum);
  } else if (double* t = seconds_.of(current_)) {
    *t += wall;
  }
  last_ = now;
}

StageSeconds StageClock::seconds() {
  enter(current_);
  StageSeconds s = seconds_;
  s.total = secondsBetween(start_, last_);
  return s;
}

}  // namespace conformesh::pipeline
