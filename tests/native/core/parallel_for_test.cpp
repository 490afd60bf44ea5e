#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel_for.h"

using conformesh::parallelFor;

TEST_CASE("parallelFor: every item runs exactly once, for every thread count") {
  for (unsigned threads : {0u, 1u, 2u, 3u, 8u})
    for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(7), size_t(1000)}) {
      std::vector<std::atomic<int>> runs(n);
      parallelFor(n, threads, [&](size_t i) { runs[i].fetch_add(1); });
      for (size_t i = 0; i < n; ++i) CHECK(runs[i].load() == 1);
    }
}

TEST_CASE("parallelFor: the exception of the lowest failing index reaches the caller") {
  for (unsigned threads : {1u, 2u, 4u})
    for (int trial = 0; trial < 20; ++trial) {
      std::string what;
      try {
        // items 37 and above fail; the later ones may run first on another thread
        parallelFor(200, threads, [&](size_t i) {
          if (i >= 37) throw std::runtime_error("item " + std::to_string(i));
        });
      } catch (const std::runtime_error& e) {
        what = e.what();
      }
      CHECK(what == "item 37");
    }
}

TEST_CASE("parallelFor: onDone runs on the calling thread with a rising count, and its exception stops the loop") {
  for (unsigned threads : {1u, 2u, 4u}) {
    const std::thread::id caller = std::this_thread::get_id();
    size_t last = 0;
    bool onCaller = true, rising = true;
    parallelFor(
        500, threads, [](size_t) {},
        [&](size_t done) {
          onCaller = onCaller && std::this_thread::get_id() == caller;
          rising = rising && done > last && done <= 500;
          last = done;
        });
    CHECK(onCaller);
    CHECK(rising);
    CHECK(last == 500);
    // a cancel after the first item: the items not yet taken never run (each takes a while, so
    // that the other threads cannot run them all before the cancel)
    std::atomic<size_t> ran{0};
    bool cancelled = false;
    try {
      parallelFor(
          10000, threads,
          [&](size_t) {
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            ran.fetch_add(1);
          },
          [&](size_t) { throw std::runtime_error("cancel"); });
    } catch (const std::runtime_error&) {
      cancelled = true;
    }
    CHECK(cancelled);
    CHECK(ran.load() < 10000);
  }
}
