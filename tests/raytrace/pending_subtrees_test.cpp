// The fast tracer's pending-subtree queue: every entry comes out once, nearest first while
// the heap has room, depth-first from the overflow stack otherwise, and minTNear() is a
// lower bound on every entry still pending.
#include "raytrace/fast/pending_subtrees.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "math/rng.h"

namespace glint {
namespace {

TEST(PendingSubtrees, PopsNearestFirstWithinTheHeap) {
  PendingSubtrees<64, 16> pending;
  Rng rng(1);
  std::vector<float> pushed;
  for (int i = 0; i < 50; ++i) {
    float t = rng.uniform() * 10.0f;
    pushed.push_back(t);
    pending.push({i, t});
  }
  std::sort(pushed.begin(), pushed.end());
  for (float t : pushed) {
    ASSERT_FALSE(pending.empty());
    EXPECT_EQ(pending.minTNear(), t);
    EXPECT_EQ(pending.pop().tNear, t);
  }
  EXPECT_TRUE(pending.empty());
}

TEST(PendingSubtrees, OverflowKeepsEveryEntryAndAValidLowerBound) {
  PendingSubtrees<4, 64> pending;
  Rng rng(2);
  std::vector<int> seen(200, 0);
  std::vector<float> tNear(200);
  std::vector<bool> inside(200, false);
  int next = 0, popped = 0;
  // Interleave pushes (in groups, like a node's children) and pops.
  while (popped < 200) {
    int group = int(rng.uniformInt(4));
    for (int k = 0; k < group && next < 200 && pending.stackSize() < 56; ++k, ++next) {
      tNear[next] = rng.uniform() * 10.0f;
      inside[next] = true;
      pending.push({next, tNear[next]});
    }
    if (pending.empty()) {
      if (next == 200) break;
      continue;
    }
    float bound = pending.minTNear();
    for (int i = 0; i < 200; ++i) {
      if (inside[i]) {
        ASSERT_LE(bound, tNear[i]);
      }
    }
    PendingSubtree s = pending.pop();
    ++seen[s.code];
    inside[s.code] = false;
    ++popped;
  }
  for (int i = 0; i < 200; ++i) EXPECT_EQ(seen[i], 1) << "entry " << i;
}

}  // namespace
}  // namespace glint
