// The fast tracer's bounded per-ray buffer of hits found but not yet composited: a binary
// min-heap ordered by (key, Gaussian id), the order every tracer composites in.
#pragma once

#include <algorithm>
#include <cstdint>

#include "raytrace/gaussian_kernel.h"

namespace glint {

// Position of a hit in compositing order: by key, ties by Gaussian id.
struct HitOrder {
  float key;
  uint32_t id;

  bool operator<(const HitOrder& b) const { return key < b.key || (key == b.key && id < b.id); }
};

// A hit as evaluateGaussian describes it (KernelHit<float>), kept trivially constructible
// so an unused buffer costs nothing to create.
struct BufferedHit {
  uint32_t id;
  float key, tPeak, tEnter, tExit, response, alpha;
  float localPoint[3];

  HitOrder order() const { return {key, id}; }
  KernelHit<double> kernelHit() const {
    return {double(tPeak), double(tEnter), double(tExit), double(key), double(response), double(alpha),
            Vec3d(localPoint[0], localPoint[1], localPoint[2])};
  }
};

template <int kCapacityLimit>
class HitBuffer {
 public:
  explicit HitBuffer(int capacity) : capacity_(std::min(capacity, kCapacityLimit)) {}

  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == capacity_; }
  int size() const { return size_; }
  const BufferedHit& nearest() const { return heap_[0]; }
  const BufferedHit& operator[](int i) const { return heap_[i]; }
  void clear() { size_ = 0; }

  void push(const BufferedHit& h) {
    // Sift up from the new leaf.
    int i = size_++;
    HitOrder key = h.order();
    while (i > 0) {
      int parent = (i - 1) / 2;
      if (!(key < heap_[parent].order())) break;
      heap_[i] = heap_[parent];
      i = parent;
    }
    heap_[i] = h;
  }

  BufferedHit popNearest() {
    BufferedHit top = heap_[0];
    BufferedHit last = heap_[--size_];
    // Sift the former last entry down from the root.
    int i = 0;
    HitOrder key = last.order();
    for (;;) {
      int child = 2 * i + 1;
      if (child >= size_) break;
      if (child + 1 < size_ && heap_[child + 1].order() < heap_[child].order()) ++child;
      if (!(heap_[child].order() < key)) break;
      heap_[i] = heap_[child];
      i = child;
    }
    if (size_ > 0) heap_[i] = last;
    return top;
  }

  // Keeps only the `keep` nearest hits (keep < size) and returns the order of the
  // nearest hit removed. A sorted array is a valid min-heap, so the rest stays a heap.
  HitOrder shrink(int keep) {
    std::sort(heap_, heap_ + size_, [](const BufferedHit& a, const BufferedHit& b) { return a.order() < b.order(); });
    HitOrder cut = heap_[keep].order();
    size_ = keep;
    return cut;
  }

 private:
  BufferedHit heap_[kCapacityLimit];
  int size_ = 0;
  int capacity_;
};

}  // namespace glint
