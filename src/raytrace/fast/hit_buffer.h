// The fast tracer's bounded per-ray buffer of hits found but not yet composited, ordered
// by (key, Gaussian id), the order every tracer composites in.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/cpu_gpu.h"
#include "raytrace/fast/bvh8_kernels.h"
#include "raytrace/fast/kernel_response.h"
#include "raytrace/gaussian_kernel.h"

namespace glint {

// Position of a hit in compositing order: by key, ties by Gaussian id.
struct HitOrder {
  float key;
  uint32_t id;

  GLINT_CPU_GPU bool operator<(const HitOrder& b) const { return key < b.key || (key == b.key && id < b.id); }
};

// What a ray keeps of a hit while it waits to be composited: the compositor reads only
// the key and alpha (and the Gaussian's attributes by id). Small, so that a ray's buffer,
// and the buffers of a bundle's 64 rays written in turn, stay in the cache.
struct KeyedHit {
  float key;
  uint32_t id;
  float alpha;

  GLINT_CPU_GPU HitOrder order() const { return {key, id}; }
  GLINT_CPU_GPU KernelHit<float> kernelHit() const { return {0.0f, 0.0f, 0.0f, key, 0.0f, alpha, Vec3f(0.0f)}; }
};

// Gaussian g of `block` as a hit, from lane `lane` of the proxy test's candidates c (a test
// that passed); false when its alpha is below alphaMin. Every walk of the 8-wide BVH, on the
// CPU and the GPU, makes its hits here, so they agree bit for bit.
GLINT_CPU_GPU inline bool makeLaneHit(const KernelResponse& response, float alphaMin, const Bvh8Block& block, int g,
                                      const Bvh8BlockCandidates& c, int lane, float tMin, KeyedHit* h) {
  const float alpha = response.alpha(block.opacity[g], c.r2[lane]);
  if (alpha < alphaMin) return false;
  *h = {hitKey(c.tPeak[lane], c.tPeak[lane] - c.half[lane], c.tPeak[lane] + c.half[lane], tMin), block.id[g], alpha};
  return true;
}

// Kept sorted, nearest first, from head_ to end_: hits arrive nearly in order (BVH
// children nearest first, bundle candidates by the bound of their key), so inserting from
// the back moves few entries, and taking the nearest is an increment. Measured faster
// than a binary heap, whose sift-down branches on every level.
template <int kCapacityLimit, typename Hit = KeyedHit>
class HitBuffer {
 public:
  explicit HitBuffer(int capacity) : capacity_(std::min(capacity, kCapacityLimit)) {}

  bool empty() const { return end_ == head_; }
  bool full() const { return end_ - head_ == capacity_; }
  int size() const { return end_ - head_; }
  const Hit& nearest() const { return hits_[head_]; }
  // The i-th nearest hit.
  const Hit& operator[](int i) const { return hits_[head_ + i]; }
  void clear() { head_ = end_ = 0; }
  // Empties the buffer and sets a new capacity (reuse without copying the storage).
  void reset(int capacity) {
    clear();
    capacity_ = std::min(capacity, kCapacityLimit);
  }

  void push(const Hit& h) {
    if (end_ == kCapacityLimit) {  // not full, so head_ > 0: slide the hits to the front
      std::copy(hits_ + head_, hits_ + end_, hits_);
      end_ -= head_;
      head_ = 0;
    }
    int i = end_++;
    HitOrder key = h.order();
    for (; i > head_ && key < hits_[i - 1].order(); --i) hits_[i] = hits_[i - 1];
    hits_[i] = h;
  }

  Hit popNearest() { return hits_[head_++]; }

  // Keeps only the `keep` nearest hits (keep < size) and returns the order of the
  // nearest hit removed.
  HitOrder shrink(int keep) {
    HitOrder cut = hits_[head_ + keep].order();
    end_ = head_ + keep;
    return cut;
  }

 private:
  Hit hits_[kCapacityLimit];
  int head_ = 0, end_ = 0;
  int capacity_;
};

}  // namespace glint
