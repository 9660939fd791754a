// Tests of the parallel loops: every index visited exactly once, thread limits applied
// and restored, and per-thread indices within range.
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <utility>
#include <vector>

namespace glint {
namespace {

TEST(ParallelFor, VisitsEveryIndexExactlyOnce) {
  for (int64_t count : {0, 1, 7, 10000}) {
    for (int64_t grain : {1, 3, 1000}) {
      std::vector<std::atomic<int>> visits(size_t(count) + 1);  // +1: never empty
      for (auto& v : visits) v = 0;
      parallelFor(count, grain, [&](int64_t i) {
        ASSERT_GE(i, 0);
        ASSERT_LT(i, count);
        visits[size_t(i)].fetch_add(1, std::memory_order_relaxed);
      });
      for (int64_t i = 0; i < count; ++i)
        ASSERT_EQ(visits[size_t(i)].load(), 1) << "index " << i << ", count " << count << ", grain " << grain;
    }
  }
}

TEST(ParallelFor, ChunksAreDisjointAndCoverTheRange) {
  for (int64_t count : {1, 7, 10000}) {
    for (int64_t grain : {1, 3, 1000}) {
      std::mutex mutex;
      std::vector<std::pair<int64_t, int64_t>> chunks;
      parallelForChunks(count, grain, [&](int64_t begin, int64_t end) {
        std::lock_guard<std::mutex> lock(mutex);
        chunks.emplace_back(begin, end);
      });
      std::sort(chunks.begin(), chunks.end());
      int64_t next = 0;
      for (auto [begin, end] : chunks) {
        EXPECT_EQ(begin, next) << "count " << count << ", grain " << grain;
        EXPECT_LT(begin, end);
        next = end;
      }
      EXPECT_EQ(next, count);
    }
  }
}

TEST(ParallelFor, NonPositiveCountsAndGrainsAreHarmless) {
  int calls = 0;
  parallelForChunks(-5, 1, [&](int64_t, int64_t) { ++calls; });
  EXPECT_EQ(calls, 0);
  std::atomic<int> visits{0};
  parallelFor(100, 0, [&](int64_t) { visits++; });  // grain 0 behaves as 1
  EXPECT_EQ(visits.load(), 100);
}

TEST(ThreadLimit, LimitsAndRestores) {
  int before = maxThreads();
  EXPECT_GE(before, 1);
  {
    ThreadLimit limit(1);
    EXPECT_EQ(maxThreads(), 1);
    parallelFor(1000, 1, [&](int64_t) { ASSERT_EQ(threadIndex(), 0); });
  }
  EXPECT_EQ(maxThreads(), before);
  {
    ThreadLimit unlimited(0);  // 0 = no limit
    EXPECT_EQ(maxThreads(), before);
  }
  EXPECT_EQ(maxThreads(), before);
}

TEST(ThreadIndex, WithinMaxThreadsInsideLoops) {
  int limit = maxThreads();
  std::atomic<int> bad{0};
  parallelFor(100000, 16, [&](int64_t) {
    int index = threadIndex();
    if (index < 0 || index >= limit) bad++;
  });
  EXPECT_EQ(bad.load(), 0);
  EXPECT_GE(threadIndex(), 0);  // outside any loop, too
  EXPECT_LT(threadIndex(), limit);
}

TEST(ThreadIndex, PerThreadScratchSumsCorrectly) {
  // The use threadIndex() exists for: one accumulator per thread, no atomics.
  std::vector<int64_t> partial(size_t(maxThreads()), 0);
  parallelForChunks(100000, 64, [&](int64_t begin, int64_t end) {
    int64_t sum = 0;
    for (int64_t i = begin; i < end; ++i) sum += i;
    partial[size_t(threadIndex())] += sum;
  });
  int64_t total = 0;
  for (int64_t p : partial) total += p;
  EXPECT_EQ(total, int64_t(100000) * 99999 / 2);
}

}  // namespace
}  // namespace glint
