// The subtrees a ray has entered but not yet visited, for the fast tracer's front-to-back
// traversal: a bounded min-heap on the entry distance (best-first order, so the ray sweeps
// forward and can stop early), which overflows into a depth-first stack (bounded by the
// tree depth) instead of growing.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

namespace glint {

struct PendingSubtree {
  int32_t code;  // inner node index, or ~leaf index (Bvh8Node)
  float tNear;   // entry distance: no hit inside has a smaller key
};

template <int kHeapCapacity, int kStackCapacity>
class PendingSubtrees {
 public:
  void clear() { heapSize_ = stackSize_ = 0; }
  bool empty() const { return heapSize_ == 0 && stackSize_ == 0; }
  int stackSize() const { return stackSize_; }

  // A lower bound on the entry distance of every pending subtree.
  float minTNear() const {
    float m = heapSize_ > 0 ? heap_[0].tNear : std::numeric_limits<float>::infinity();
    return stackSize_ > 0 ? std::min(m, stack_[stackSize_ - 1].pendingMin) : m;
  }

  // While the heap is full, entries go on the stack; the caller (who checked the stack
  // bound at build) pushes siblings farthest first so the nearest is popped first.
  void push(PendingSubtree s) {
    if (heapSize_ < kHeapCapacity) {
      int i = heapSize_++;
      while (i > 0) {
        int parent = (i - 1) / 2;
        if (!(s.tNear < heap_[parent].tNear)) break;
        heap_[i] = heap_[parent];
        i = parent;
      }
      heap_[i] = s;
      return;
    }
    float below = stackSize_ > 0 ? stack_[stackSize_ - 1].pendingMin : std::numeric_limits<float>::infinity();
    stack_[stackSize_++] = {s, std::min(s.tNear, below)};
  }

  // The stack first (it drains one subtree depth-first while the heap stays full), else
  // the nearest subtree.
  PendingSubtree pop() {
    if (stackSize_ > 0) return stack_[--stackSize_].subtree;
    PendingSubtree top = heap_[0];
    PendingSubtree last = heap_[--heapSize_];
    int i = 0;
    for (;;) {
      int child = 2 * i + 1;
      if (child >= heapSize_) break;
      if (child + 1 < heapSize_ && heap_[child + 1].tNear < heap_[child].tNear) ++child;
      if (!(heap_[child].tNear < last.tNear)) break;
      heap_[i] = heap_[child];
      i = child;
    }
    if (heapSize_ > 0) heap_[i] = last;
    return top;
  }

 private:
  struct StackEntry {
    PendingSubtree subtree;
    float pendingMin;  // smallest tNear of this entry and every entry below it
  };
  PendingSubtree heap_[kHeapCapacity];
  StackEntry stack_[kStackCapacity];
  int heapSize_ = 0;
  int stackSize_ = 0;
};

}  // namespace glint
