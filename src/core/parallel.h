// Parallel loops: the one place Glint creates threads (oneTBB underneath).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

namespace glint {

// Limits the worker threads of every later parallel loop (0 = all cores). Lives for
// the lifetime of the returned object.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Number of threads parallel loops may use now.
int maxThreads();

// Calls body(begin, end) on disjoint chunks covering [0, count), in parallel.
// grain is the smallest chunk worth handing to a thread.
void parallelForChunks(int64_t count, int64_t grain, const std::function<void(int64_t, int64_t)>& body);

// Calls body(i) for each i in [0, count), in parallel.
template <typename Body>
void parallelFor(int64_t count, int64_t grain, Body&& body) {
  parallelForChunks(count, grain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) body(i);
  });
}

// Index of the calling worker thread in [0, threadSlotCount()), for per-thread scratch
// space. (Under a ThreadLimit below the core count, oneTBB may still hand out slot
// numbers up to the machine's concurrency, so size scratch arrays by threadSlotCount().)
int threadIndex();
int threadSlotCount();

}  // namespace glint
