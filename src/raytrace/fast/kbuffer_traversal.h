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

// Stack entries of one pass.
constexpr int kKBufferStackCapacity = 192;

// Whether a depth-first walk of the tree fits the stack: its depth bound plus a node's
// children pushed at once.
inline bool fitsKBufferStack(const Bvh8& bvh) { return bvh.maxStackSize() + kBvhWidth <= kKBufferStackCapacity; }

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
  // Returns where h went, or -1 when it did not fit; *lost is set when a hit was lost (h,
  // or the farthest one pushed out).
  GLINT_CPU_GPU int insert(const KeyedHit& h, bool* lost) {
    const HitOrder order = h.order();
    const bool wasFull = size_ == K;
    if (wasFull) *lost = true;
    if (wasFull && !(order < hits_[K - 1].order())) return -1;
    int i = wasFull ? K - 1 : size_++;
    for (; i > 0 && order < hits_[i - 1].order(); --i) hits_[i] = hits_[i - 1];
    hits_[i] = h;
    return i;
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

// One ray's state in the k-buffer traversal, pass by pass: what both the per-ray walk below
// and the GPU's warp-wide walk (cuda/warp_traversal.cuh) do at a node, at a leaf and at the
// end of a pass. Only the order of the walk, the stack, differs between them.
template <int K, typename Recorder>
class KBufferRay {
 public:
  GLINT_CPU_GPU KBufferRay(const GaussianAttributes& attributes, const TraceSettings& settings,
                           const TraceRay& traceRay, Recorder recorder)
      : compositor_(attributes, settings, recorder),
        settings_(settings),
        ray_(traceRay),
        response_(settings.kernelPower) {
    if (traceRay.backfaceSkip > 0) compositor_.skipBackfacing(traceRay.direction, traceRay.backfaceSkip);
  }

  GLINT_CPU_GPU float tMin() const { return ray_.tMin; }

  // Starts a pass: an empty buffer, no cutoff yet.
  GLINT_CPU_GPU void startPass() {
    buffer_ = NearestHits<K>();
    hasCutoff_ = false;
    lost_ = false;
    startTransmittance_ = float(compositor_.transmittance());
  }

  // Whether a subtree entered at tNear can be passed over: it lies behind the cutoff, or
  // behind a full buffer's farthest hit (its hits are then lost to this pass).
  GLINT_CPU_GPU bool skips(float tNear) {
    if (hasCutoff_ && tNear > cutoff_.key) return true;
    if (!tail_ && buffer_.full() && tNear > buffer_.farthest().key) {
      lost_ = true;
      return true;
    }
    return false;
  }

  // The children of `node` to visit: those the ray enters that are not wholly before lo
  // (every key is at most the box's exit distance) nor skipped; tNear receives their entry
  // distances.
  GLINT_CPU_GPU uint32_t children(const Bvh8Node& node, float tNear[kBvhWidth]) {
    float tFar[kBvhWidth];
    const uint32_t mask = intersectNodeScalar(node, ray_, tNear, tFar);
    uint32_t keep = 0;
    GLINT_UNROLL
    for (int c = 0; c < kBvhWidth; ++c) {
      if (!(mask >> c & 1u)) continue;
      if (hasLo_ && tFar[c] < lo_.key) continue;
      if (skips(tNear[c])) continue;
      keep |= 1u << c;
    }
    return keep;
  }

  // Tests the Gaussians of a leaf: the hits behind lo go to the buffer (or, in the exact
  // tail's last pass, straight into the final transmittance).
  GLINT_CPU_GPU void visitLeaf(const Bvh8View& bvh, int32_t code) {
    const Bvh8Block* blocks = bvh.blocks + Bvh8Node::leafFirstBlock(code);
    const int count = Bvh8Node::leafBlocks(code);
    for (int b = 0; b < count; ++b) {
      const Bvh8Block& block = blocks[b];
      for (int i = 0; i < kBvhWidth; ++i) {
        Bvh8BlockCandidates c;
        KeyedHit h;
        if (proxyTestScalar(block, i, ray_.origin, ray_.direction, ray_.tMin, &c, 0) &&
            makeLaneHit(response_, settings_.alphaMin, block, i, c, 0, ray_.tMin, &h))
          accept(h);
      }
    }
  }

  // Composites the pass's buffer; returns true when the ray is done (terminated, or every
  // hit composited), false when another pass must continue behind the buffer.
  GLINT_CPU_GPU bool finishPass() {
    if (tail_) return true;
    for (int i = 0; i < buffer_.size(); ++i) {
      if (compositor_.add(buffer_[i].id, buffer_[i].kernelHit())) continue;
      if (!settings_.exactTail) return true;
      // Terminated: the buffer's remaining hits only multiply into the tail; the last
      // pass takes every hit behind this buffer.
      tail_ = true;
      for (int j = i + 1; j < buffer_.size(); ++j) compositor_.add(buffer_[j].id, buffer_[j].kernelHit());
      break;
    }
    // Without a lost hit, every hit behind lo (and before the cutoff) was in the buffer.
    if (!lost_ || buffer_.size() == 0) return true;
    lo_ = buffer_.farthest().order();
    hasLo_ = true;
    return false;
  }

  GLINT_CPU_GPU RayResult finish() const { return compositor_.finish(); }

 private:
  GLINT_CPU_GPU void accept(const KeyedHit& h) {
    if (hasLo_ && !(lo_ < h.order())) return;  // composited in an earlier pass
    if (tail_) {
      compositor_.add(h.id, h.kernelHit());
      return;
    }
    if (compositor_.skips(h.id, h.key)) return;  // invisible to the compositor
    if (hasCutoff_ && !(h.order() < cutoff_)) return;
    const int at = buffer_.insert(h, &lost_);
    if (at < 0 || settings_.exactTail) return;
    // Where the buffered hits end the ray, compositing as the compositor does. The
    // transmittance after the hits before `at` is unchanged; only from `at` on is it new.
    float t = at == 0 ? startTransmittance_ : transmittanceAfter_[at - 1];
    for (int k = at; k < buffer_.size(); ++k) {
      t *= 1.0f - buffer_[k].alpha;
      transmittanceAfter_[k] = t;
      if (t < settings_.minTransmittance) {
        cutoff_ = buffer_[k].order();
        hasCutoff_ = true;
        buffer_.truncate(k + 1);
        return;
      }
    }
  }

  Compositor<float, Recorder> compositor_;
  const TraceSettings& settings_;
  Bvh8Ray ray_;
  KernelResponse response_;
  HitOrder lo_{0.0f, 0};
  bool hasLo_ = false;
  // Terminated with exactTail: the last pass multiplies every hit behind lo into the
  // final transmittance, in any order.
  bool tail_ = false;
  // This pass: the buffer; the buffered hit at which the transmittance (from the hits
  // composited in earlier passes and the buffered ones) falls below the threshold, without
  // the exact tail; whether a hit behind lo (and before the cutoff) did not fit.
  NearestHits<K> buffer_;
  float transmittanceAfter_[K];  // the buffered hits' transmittance, hit k's included
  HitOrder cutoff_{0.0f, 0};
  bool hasCutoff_ = false;
  bool lost_ = false;
  float startTransmittance_ = 1.0f;
};

// Where child c of `keep` goes on a stack that pops the nearest first: its rank among the
// kept children by decreasing entry distance, ties by lane, computed without a sort so that
// nothing is indexed at run time.
GLINT_CPU_GPU inline int farthestFirstRank(uint32_t keep, const float tNear[kBvhWidth], int c) {
  int rank = 0;
  GLINT_UNROLL
  for (int d = 0; d < kBvhWidth; ++d)
    rank += int((keep >> d & 1u) && (tNear[d] > tNear[c] || (tNear[d] == tNear[c] && d < c)));
  return rank;
}

// Pushes the children of `keep` farthest first; returns how many.
GLINT_CPU_GPU inline int pushNearestLast(const Bvh8Node& node, uint32_t keep, const float tNear[kBvhWidth],
                                         int32_t* stack, float* stackNear) {
  int count = 0;
  GLINT_UNROLL
  for (int c = 0; c < kBvhWidth; ++c) {
    if (!(keep >> c & 1u)) continue;
    const int rank = farthestFirstRank(keep, tNear, c);
    stack[rank] = node.child[c];
    stackNear[rank] = tNear[c];
    ++count;
  }
  return count;
}

// Traces one ray through `bvh`, compositing into a Compositor that records its hits with
// `recorder`: each pass walks the tree depth-first with the ray's own stack. The tree must
// fit the stack (fitsKBufferStack; callers check it once per build).
template <int K, typename Recorder>
GLINT_CPU_GPU RayResult traceKBuffer(const Bvh8View& bvh, const GaussianAttributes& attributes,
                                     const TraceSettings& settings, const TraceRay& traceRay, Recorder recorder,
                                     KBufferTraceStats* stats = nullptr) {
  KBufferRay<K, Recorder> ray(attributes, settings, traceRay, recorder);
  if (bvh.empty) return ray.finish();
  for (bool done = false; !done;) {
    if (stats) ++stats->passes;
    ray.startPass();
    int32_t stack[kKBufferStackCapacity];
    float stackNear[kKBufferStackCapacity];
    int top = 0;
    stack[top] = 0, stackNear[top] = ray.tMin(), ++top;
    while (top > 0) {
      --top;
      const int32_t code = stack[top];
      // Every hit in the subtree has a key at least its entry distance.
      if (ray.skips(stackNear[top])) continue;
      if (Bvh8Node::isLeaf(code)) {
        if (stats) stats->blocks += Bvh8Node::leafBlocks(code);
        ray.visitLeaf(bvh, code);
        continue;
      }
      if (stats) ++stats->nodes;
      const Bvh8Node& node = bvh.nodes[code];
      float tNear[kBvhWidth];
      uint32_t keep = ray.children(node, tNear);
      if (top + kBvhWidth > kKBufferStackCapacity) keep = 0;  // never: callers check the depth bound
      top += pushNearestLast(node, keep, tNear, stack + top, stackNear + top);
    }
    done = ray.finishPass();
  }
  return ray.finish();
}

}  // namespace glint
