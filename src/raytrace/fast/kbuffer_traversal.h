// The GPU's traversal of the 8-wide BVH, written once for the CPU and the GPU (the CPU tests
// run it against the fast tracer): each pass walks the tree depth-first, nearest child
// first, keeping the K nearest hits beyond the last composited one in a sorted buffer; the
// hits are then composited in (key, id) order and, while the ray has not terminated and the
// buffer was full, the next pass continues behind them. Subtrees that start behind the
// buffer's farthest hit once it is full are skipped, and so, without the exact tail, is
// everything behind the hit where the buffered hits alone already end the ray: hits found
// later only come before it and lower the transmittance further, so the ray ends there or
// sooner. The composited hits, their order and their alphas are exactly those of the CPU's
// streaming traversal (fast_tracer.cpp).
#pragma once

#include <cstdint>

#include "core/cpu_gpu.h"
#include "raytrace/compositor.h"
#include "raytrace/fast/bvh8.h"
#include "raytrace/fast/bvh8_kernels.h"
#include "raytrace/fast/hit_buffer.h"
#include "raytrace/fast/kernel_response.h"

namespace glint {

// The tree as plain arrays (host or device memory).
struct Bvh8View {
  const Bvh8Node* nodes = nullptr;
  const Bvh8Block* blocks = nullptr;
  bool empty = true;
};

// Recorders of composited hits for traceKBuffer: none, or a fixed array (the GPU's).
struct NoHitRecorder {
  GLINT_CPU_GPU void record(const HitRecord&) {}
};

struct ArrayHitRecorder {
  HitRecord* hits;
  uint32_t capacity;
  uint32_t* count;
  bool* overflowed;

  GLINT_CPU_GPU void record(const HitRecord& hit) {
    if (*count < capacity)
      hits[(*count)++] = hit;
    else
      *overflowed = true;
  }
};

// Hits a ray keeps per pass on the GPU.
constexpr int kGpuKBufferHits = 32;

// Stack entries of one pass: the tree's depth bound (Bvh8::maxStackSize) must fit.
constexpr int kKBufferStackCapacity = 192;

// A ray's K nearest hits found so far in a pass, nearest first.
template <int K>
class NearestHits {
 public:
  GLINT_CPU_GPU bool full() const { return size_ == K; }
  GLINT_CPU_GPU int size() const { return size_; }
  GLINT_CPU_GPU const KeyedHit& operator[](int i) const { return hits_[i]; }
  GLINT_CPU_GPU const KeyedHit& farthest() const { return hits_[size_ - 1]; }
  // Keeps the n nearest hits.
  GLINT_CPU_GPU void truncate(int n) { size_ = n < size_ ? n : size_; }

  // Inserts h in order; when full, h replaces the farthest hit if it comes before it.
  // Returns false when a hit was lost (h, or the farthest one).
  GLINT_CPU_GPU bool insert(const KeyedHit& h) {
    const HitOrder order = h.order();
    const bool wasFull = size_ == K;
    if (wasFull && !(order < hits_[K - 1].order())) return false;
    int i = wasFull ? K - 1 : size_++;
    for (; i > 0 && order < hits_[i - 1].order(); --i) hits_[i] = hits_[i - 1];
    hits_[i] = h;
    return !wasFull;  // when full, the farthest hit was pushed out
  }

 private:
  KeyedHit hits_[K];
  int size_ = 0;
};

// What a ray cost (benchmarks and tests).
struct KBufferTraceStats {
  int passes = 0;
  int nodes = 0;   // inner nodes visited
  int blocks = 0;  // 8-lane leaf blocks tested
};

// Traces one ray through `bvh`, compositing into a Compositor that records its hits with
// `recorder`. The tree's maxStackSize() must not exceed kKBufferStackCapacity (callers
// check it once per build).
template <int K, typename Recorder>
GLINT_CPU_GPU RayResult traceKBuffer(const Bvh8View& bvh, const GaussianAttributes& attributes,
                                     const TraceSettings& settings, const TraceRay& traceRay, Recorder recorder,
                                     KBufferTraceStats* stats = nullptr) {
  Compositor<float, Recorder> compositor(attributes, settings, recorder);
  if (traceRay.backfaceSkip > 0) compositor.skipBackfacing(traceRay.direction, traceRay.backfaceSkip);
  if (bvh.empty) return compositor.finish();
  const Bvh8Ray ray(traceRay);
  const KernelResponse response(settings.kernelPower);
  HitOrder lo{0.0f, 0};
  bool hasLo = false;
  // Terminated with exactTail: the last pass multiplies every hit behind `lo` into the
  // final transmittance, in any order.
  bool tail = false;
  const float minTransmittance = settings.minTransmittance;
  for (;;) {
    if (stats) ++stats->passes;
    NearestHits<K> buffer;
    // Without the exact tail: the buffered hit at which the transmittance, from the hits
    // composited in earlier passes and the buffered ones, falls below the threshold.
    HitOrder cutoff{0.0f, 0};
    bool hasCutoff = false;
    // A hit behind lo (and before the cutoff) did not fit the buffer: another pass follows.
    bool lost = false;
    const float startTransmittance = float(compositor.transmittance());
    int32_t stack[kKBufferStackCapacity];
    float stackNear[kKBufferStackCapacity];
    int top = 0;
    stack[top] = 0, stackNear[top] = ray.tMin, ++top;
    while (top > 0) {
      --top;
      const int32_t code = stack[top];
      // Every hit in the subtree has a key at least its entry distance.
      if (hasCutoff && stackNear[top] > cutoff.key) continue;
      if (!tail && buffer.full() && stackNear[top] > buffer.farthest().key) {
        lost = true;
        continue;
      }
      if (Bvh8Node::isLeaf(code)) {
        const Bvh8Block* blocks = bvh.blocks + Bvh8Node::leafFirstBlock(code);
        const int count = Bvh8Node::leafBlocks(code);
        if (stats) stats->blocks += count;
        for (int b = 0; b < count; ++b) {
          const Bvh8Block& block = blocks[b];
          for (int i = 0; i < kBvhWidth; ++i) {
            Bvh8BlockCandidates c;
            if (!proxyTestScalar(block, i, ray.origin, ray.direction, ray.tMin, &c, 0)) continue;
            const float alpha = response.alpha(block.opacity[i], c.r2[0]);
            if (alpha < settings.alphaMin) continue;
            const KeyedHit h{hitKey(c.tPeak[0], c.tPeak[0] - c.half[0], c.tPeak[0] + c.half[0], ray.tMin),
                             block.id[i], alpha};
            if (hasLo && !(lo < h.order())) continue;  // composited in an earlier pass
            if (tail) {
              compositor.add(h.id, h.kernelHit());
              continue;
            }
            if (compositor.skips(h.id, h.key)) continue;  // invisible to the compositor
            if (hasCutoff && !(h.order() < cutoff)) continue;
            lost |= !buffer.insert(h);
            if (settings.exactTail) continue;
            // Where the buffered hits end the ray, compositing as the compositor does.
            float t = startTransmittance;
            for (int k = 0; k < buffer.size(); ++k) {
              t *= 1.0f - buffer[k].alpha;
              if (t < minTransmittance) {
                cutoff = buffer[k].order();
                hasCutoff = true;
                buffer.truncate(k + 1);
                break;
              }
            }
          }
        }
        continue;
      }
      if (stats) ++stats->nodes;
      const Bvh8Node& node = bvh.nodes[code];
      float tNear[kBvhWidth], tFar[kBvhWidth];
      const uint32_t mask = intersectNodeScalar(node, ray, tNear, tFar);
      // The children that can still hold a hit to keep: not wholly before lo (every key is
      // at most the box's exit distance), nor behind the cutoff or a full buffer's farthest.
      uint32_t keep = 0;
      GLINT_UNROLL
      for (int c = 0; c < kBvhWidth; ++c) {
        if (!(mask >> c & 1u)) continue;
        if (hasLo && tFar[c] < lo.key) continue;
        if (hasCutoff && tNear[c] > cutoff.key) continue;
        if (!tail && buffer.full() && tNear[c] > buffer.farthest().key) {
          lost = true;
          continue;
        }
        keep |= 1u << c;
      }
      // Pushed farthest first (so the nearest is visited next): child c goes to its rank
      // among the kept children by decreasing entry distance, ties by lane, computed
      // without a sort so that nothing is indexed at run time.
      int count = 0;
      GLINT_UNROLL
      for (int c = 0; c < kBvhWidth; ++c) count += int(keep >> c & 1u);
      if (top + count > kKBufferStackCapacity) count = 0, keep = 0;  // never: the depth bound is checked at build
      GLINT_UNROLL
      for (int c = 0; c < kBvhWidth; ++c) {
        if (!(keep >> c & 1u)) continue;
        int rank = 0;
        GLINT_UNROLL
        for (int d = 0; d < kBvhWidth; ++d)
          rank += int((keep >> d & 1u) && (tNear[d] > tNear[c] || (tNear[d] == tNear[c] && d < c)));
        stack[top + rank] = node.child[c];
        stackNear[top + rank] = tNear[c];
      }
      top += count;
    }
    if (tail) break;
    // Every hit behind lo (and before the cutoff) is in the buffer.
    const bool complete = !lost;
    for (int i = 0; i < buffer.size(); ++i) {
      if (compositor.add(buffer[i].id, buffer[i].kernelHit())) continue;
      if (!settings.exactTail) return compositor.finish();
      // Terminated: the buffer's remaining hits only multiply into the tail.
      tail = true;
      for (int j = i + 1; j < buffer.size(); ++j) compositor.add(buffer[j].id, buffer[j].kernelHit());
      break;
    }
    if (complete || buffer.size() == 0) break;
    lo = buffer.farthest().order();
    hasLo = true;
  }
  return compositor.finish();
}

}  // namespace glint
