#include <doctest/doctest.h>

#include <chrono>
#include <thread>

#include "remesh/pipeline.h"

using namespace conformesh;
using pipeline::StageClock;

namespace {
double sumOfStages(const StageSeconds& s) {
  double sum = 0;
  for (Stage st : kRemeshStages) sum += *s.of(st);
  return sum;
}
}  // namespace

TEST_CASE("stage clock: a parallel section's wall time is split by its stages' thread-seconds") {
  StageClock clock(Stage::Validate);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  clock.enter(Stage::Refine);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  StageSeconds busy;
  busy.refine = 3.0;  // thread-seconds: refine three times lift
  busy.lift = 1.0;
  clock.split(busy);
  const StageSeconds s = clock.seconds();
  CHECK(s.validate > 0);
  CHECK(s.lift > 0);
  // refine stays current after the split: the moment up to seconds() is its too
  CHECK(s.refine == doctest::Approx(3.0 * s.lift).epsilon(0.05));
  CHECK(s.optimize == 0);
  // the split section's share is its wall time, not the thread-seconds (4 of them here)
  CHECK(s.refine + s.lift < 1.0);
  CHECK(sumOfStages(s) == doctest::Approx(s.total).epsilon(1e-9));
}

TEST_CASE("stage clock: a section with no thread-seconds goes to the current stage") {
  StageClock clock(Stage::Optimize);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  clock.split(StageSeconds{});
  const StageSeconds s = clock.seconds();
  CHECK(s.optimize > 0);
  CHECK(s.refine == 0);
  CHECK(sumOfStages(s) == doctest::Approx(s.total).epsilon(1e-9));
}
