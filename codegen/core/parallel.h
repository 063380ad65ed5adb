// facet — one loop over indices on several threads: the reference ray caster's
// rows, the physics estimates, the renders and processes the analyses run side by side.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace facet {

// Calls body(i) once for every i in [0, count), on `threads` threads at most (0:
// one per core; never more than count). Indices are handed out in increasing
// order, one at a time, to whichever thread is free, so the results are the
// serial loop's whenever each call writes only what belongs to its own i. The
// first exception a call throws stops the handing out and is rethrown here once
// every thread has finished.
inline void parallel_for(size_t count, unsigned threads, const std::function<void(size_t)>& body) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const size_t n = std::min<size_t>(threads, count);
  if (n <= 1) {
    for (size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::mutex mutex;
  auto work = [&] {
    for (size_t i; (i = next++) < count;) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t k = 0; k < n; ++k) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace facet
