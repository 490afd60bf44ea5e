// The threaded WebAssembly build's runtime under Node (CTest, build/wasm): parallelFor on
// pthreads, and C++ exceptions thrown and caught on several threads at once (clang 14 needs
// bindings/threads/wasm_eh_threads.cpp for any catch to match under -pthread). Exit status 0 when
// every check holds; each failure is printed.
#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel_for.h"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::printf("FAILED: %s\n", what);
    ++failures;
  }
}

struct Odd : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct Even : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void thrower(int i) {
  std::vector<int> owned(8, i);  // a destructor on the unwinding path
  if (i % 2) throw Odd(std::to_string(i));
  throw Even(std::to_string(i));
}

// Throws and catches (typed, rethrown, caught again by type) `rounds` times; the count caught right.
int throwAndCatch(int seed, int rounds) {
  int right = 0;
  for (int i = seed; i < seed + rounds; ++i) {
    try {
      try {
        thrower(i);
      } catch (const Even&) {
        if (i % 4 == 0) {
          right += i % 2 == 0;
          continue;
        }
        throw;
      }
    } catch (const Odd& e) {
      right += i % 2 == 1 && std::stoi(e.what()) == i;
    } catch (const Even& e) {
      right += i % 4 == 2 && std::stoi(e.what()) == i;
    } catch (...) {
    }
  }
  return right;
}

}  // namespace

int main() {
  using conformesh::parallelFor;
  check(conformesh::resolveThreads(0) >= 1, "resolveThreads(0) is at least 1");

  // every item once, from the pool's threads and the caller
  std::vector<int> seen(1000, 0);
  parallelFor(seen.size(), 3, [&](size_t i) { seen[i] += 1; });
  bool once = true;
  for (int s : seen) once = once && s == 1;
  check(once, "parallelFor on 3 threads runs every item once");

  // more threads than the pool has: the loop still finishes (pthread_create fails, EAGAIN)
  std::atomic<int> sum{0};
  parallelFor(64, 64, [&](size_t i) { sum += int(i); });
  check(sum == 64 * 63 / 2, "parallelFor asked for more threads than the pool has");

  // a loop inside a loop's item runs (serially on a pool thread) instead of waiting forever
  std::vector<int> inner(8, 0);
  parallelFor(8, 2, [&](size_t i) { parallelFor(4, 2, [&](size_t) { inner[i] += 1; }); });
  bool nested = true;
  for (int v : inner) nested = nested && v == 4;
  check(nested, "a nested parallelFor runs every item");

  // the lowest failing item's exception reaches the caller, every time
  for (int round = 0; round < 50; ++round) {
    std::string caught;
    try {
      parallelFor(40, 3, [&](size_t i) {
        if (i == 7 || i == 23) throw std::runtime_error("item " + std::to_string(i));
      });
    } catch (const std::runtime_error& e) {
      caught = e.what();
    }
    if (caught != "item 7") {
      check(false, "parallelFor rethrows the lowest failing item's exception");
      break;
    }
  }

  // exceptions thrown and caught on 3 threads at once
  const int rounds = 4000;
  std::vector<int> right(3, 0);
  parallelFor(3, 3, [&](size_t t) { right[t] = throwAndCatch(int(t) * rounds, rounds); });
  for (int r : right) check(r == rounds, "every exception caught by the right handler on concurrent threads");

  std::printf("%s\n", failures ? "threads test: failures" : "threads test: ok");
  return failures ? 1 : 0;
}
