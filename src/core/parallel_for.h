// conformesh — the library's one parallel loop: fn(i) for i in [0, n) on a few std::threads, the
// caller's among them. Each item writes only what it owns, so the results are the same for every
// thread count; the caller merges them in item order.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace conformesh {

//! The thread count a `threads` option stands for: 0 the hardware's concurrency (at least 1), else
//! `threads`. Always 1 in a WebAssembly build without pthreads.
unsigned resolveThreads(unsigned threads);

//! Call fn(i) for every i in [0, n) on up to resolveThreads(threads) threads, the calling thread
//! one of them; items are taken in increasing order from a shared counter. fn must write only
//! what item i owns. Returns when every item taken has finished.
//!
//! Errors: an exception thrown by fn stops the taking of new items, and the one of the lowest
//! index is rethrown on the caller: the one a serial loop would throw (every item below it was
//! taken before it and has finished). onDone (optional) runs on the calling thread only, with the
//! count of items finished so far, after each item it runs and whenever a worker finishes one
//! while it waits; an exception from it (a cancel) stops the taking of new items and is rethrown
//! once the items already taken have finished. One thread (or a build without threads): the plain
//! loop, fn(i) then onDone(i + 1). The WebAssembly build with pthreads runs the plain loop too when
//! called from a thread other than the module's main thread (a nested loop), and on fewer threads
//! when its thread pool runs out.
void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& fn,
                 const std::function<void(size_t)>& onDone = {});

//! The indices of `cost` by decreasing cost (ties by index): items of uneven cost given to
//! parallelFor in this order end closer together (the longest first, the short ones fill in).
std::vector<size_t> largestFirst(const std::vector<double>& cost);

}  // namespace conformesh
