#include "core/parallel_for.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
#define CONFORMESH_NO_THREADS 1
#else
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>
#endif
#ifdef __EMSCRIPTEN_PTHREADS__
#include <emscripten/threading.h>
#endif

namespace conformesh {
namespace {

void serialFor(size_t n, const std::function<void(size_t)>& fn, const std::function<void(size_t)>& onDone) {
  for (size_t i = 0; i < n; ++i) {
    fn(i);
    if (onDone) onDone(i + 1);
  }
}

}  // namespace

std::vector<size_t> largestFirst(const std::vector<double>& cost) {
  std::vector<size_t> order(cost.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost[a] > cost[b]; });
  return order;
}

#ifdef CONFORMESH_NO_THREADS

unsigned resolveThreads(unsigned) { return 1; }

void parallelFor(size_t n, unsigned, const std::function<void(size_t)>& fn, const std::function<void(size_t)>& onDone) {
  serialFor(n, fn, onDone);
}

#else

unsigned resolveThreads(unsigned threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& fn, const std::function<void(size_t)>& onDone) {
  size_t count = std::min<size_t>(resolveThreads(threads), n);
#ifdef __EMSCRIPTEN_PTHREADS__
  // Emscripten starts a pthread's thread from the module's main thread only: asked from a pthread
  // (a nested loop), the start waits for that thread's event loop, blocked here waiting for it.
  if (!emscripten_is_main_runtime_thread()) count = 1;
#endif
  if (count <= 1) return serialFor(n, fn, onDone);
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mu;
  std::condition_variable changed;
  // guarded by mu
  size_t done = 0, exited = 0, failedAt = SIZE_MAX;
  std::exception_ptr failure;
  // run one item; false when none is left or the loop stops
  const auto runOne = [&]() {
    if (stop.load()) return false;
    const size_t i = next.fetch_add(1);
    if (i >= n) return false;
    std::exception_ptr e;
    try {
      fn(i);
    } catch (...) {
      e = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mu);
      ++done;
      if (e) {
        stop.store(true);
        if (i < failedAt) failedAt = i, failure = e;
      }
    }
    changed.notify_all();
    return true;
  };
  std::vector<std::thread> workers;
  try {
    for (size_t k = 1; k < count; ++k)
      workers.emplace_back([&] {
        while (runOne()) {
        }
        {
          std::lock_guard<std::mutex> lock(mu);
          ++exited;
        }
        changed.notify_all();
      });
  } catch (const std::system_error&) {
    // no more threads to be had: the ones started and the caller do the work
  }
  std::exception_ptr cancel;
  size_t reported = 0;
  const auto report = [&](size_t finished) {
    if (!onDone || cancel || finished == reported) return;
    reported = finished;
    try {
      onDone(finished);
    } catch (...) {
      cancel = std::current_exception();
      stop.store(true);
    }
  };
  const auto finishedNow = [&] {
    std::lock_guard<std::mutex> lock(mu);
    return done;
  };
  while (runOne()) report(finishedNow());
  for (;;) {
    size_t finished;
    {
      std::unique_lock<std::mutex> lock(mu);
      changed.wait(lock, [&] { return exited == workers.size() || (onDone && !cancel && done != reported); });
      if (exited == workers.size()) break;
      finished = done;
    }
    report(finished);
  }
  for (std::thread& t : workers) t.join();
  if (failure) std::rethrow_exception(failure);
  if (cancel) std::rethrow_exception(cancel);
  report(done);
}

#endif

}  // namespace conformesh
