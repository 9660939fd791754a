// Exact front-to-back traversal of the 8-wide BVH: subtrees are visited nearest entry first,
// buffered hits are composited as soon as no pending subtree can still hold a nearer one,
// traversal stops when the ray terminates, and the bounded hit buffer overflows into
// further passes.
#include "raytrace/fast/fast_tracer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "raytrace/compositor.h"
#include "raytrace/fast/bvh8_kernels.h"
#include "raytrace/fast/hit_buffer.h"
#include "raytrace/fast/pending_subtrees.h"

namespace glint {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Pending subtrees ordered by entry distance; more overflow into a depth-first stack,
// which the tree's bounded depth keeps within kStackCapacity (checked at build).
constexpr int kHeapCapacity = 256;
constexpr int kStackCapacity = 512;
using Pending = PendingSubtrees<kHeapCapacity, kStackCapacity>;

// The state of one ray. Each pass traverses the tree once and accepts the hits whose
// (key, id) lies in [lo, hi); hi starts unbounded and drops when the buffer overflows, in
// which case the next pass continues from there.
class RayTraversal {
 public:
  RayTraversal(const Bvh8& bvh, const TraceRay& ray, int capacity, HitList* hits, FastTraceStats* stats)
      : bvh_(bvh),
        settings_(bvh.settings()),
        ray_(ray),
        compositor_(*bvh.scene(), bvh.settings(), hits),
        buffer_(capacity),
        capacity_(capacity),
        stats_(stats) {
    if (ray.backfaceSkip > 0) compositor_.skipBackfacing(ray.direction, ray.backfaceSkip);
    float p = settings_.kernelPower;
    integerPower_ = (p == std::round(p) && p >= 1.0f && p <= 4.0f) ? int(p) : 0;
  }

  RayResult run() {
    if (!bvh_.empty()) {
      for (;;) {
        if (!pass()) break;  // terminated, and the exact tail is not wanted
        if (!hiLowered_) break;
        lo_ = hi_, hasLo_ = true, hasHi_ = false;
      }
    }
    return compositor_.finish();
  }

 private:
  // Returns false when the ray is finished (terminated without exact tail).
  bool pass() {
    ++stats_->passes;
    buffer_.clear();
    hiLowered_ = false;
    pending_.clear();
    PendingSubtree next{0, ray_.tMin};
    bool haveNext = true;  // the nearest pending subtree, kept out of the heap
    while (haveNext || !pending_.empty()) {
      PendingSubtree s = haveNext ? next : pending_.pop();
      haveNext = false;
      // No hit not yet found can come before this bound: every one lies in s or in
      // another pending subtree.
      float bound = std::min(s.tNear, pending_.minTNear());
      if (!tail_ && !buffer_.empty() && !compositeBelow(bound)) return false;
      if (Bvh8Node::isLeaf(s.code)) {
        if (!visitLeaf(s.code, bound)) return false;
      } else {
        haveNext = visitNode(bvh_.nodes()[s.code], &next);
      }
    }
    return tail_ || compositeBelow(kInfinity);
  }

  // Adds the children the ray enters to the pending subtrees, farthest first (for the
  // depth-first overflow), except the nearest when no pending subtree starts before it:
  // that one goes to *next (returns true), saving a heap round trip.
  bool visitNode(const Bvh8Node& node, PendingSubtree* next) {
    ++stats_->nodes;
    alignas(32) float tNear[kBvhWidth];
    uint32_t mask = intersectNode(node, ray_, tNear);
    PendingSubtree hit[kBvhWidth];
    int n = 0;
    for (; mask; mask &= mask - 1) {
      int c = std::countr_zero(mask);
      PendingSubtree child{node.child[c], tNear[c]};
      int k = n++;
      for (; k > 0 && hit[k - 1].tNear < child.tNear; --k) hit[k] = hit[k - 1];
      hit[k] = child;
    }
    if (n == 0) return false;
    bool direct = hit[n - 1].tNear <= pending_.minTNear();
    if (direct) *next = hit[--n];
    for (int k = 0; k < n; ++k) pending_.push(hit[k]);
    return direct;
  }

  // Evaluates the leaf's Gaussians; `bound` is a lower bound on the key of every hit not
  // yet found (this leaf's and the pending subtrees'). The blocks are tested first, all
  // of them, so their independent arithmetic overlaps.
  bool visitLeaf(int32_t code, float bound) {
    const Bvh8Block* blocks = bvh_.blocks() + Bvh8Node::leafFirstBlock(code);
    int count = Bvh8Node::leafBlocks(code);
    Bvh8BlockCandidates c[kMaxLeafBlocks];
    uint32_t masks[kMaxLeafBlocks];
    for (int b = 0; b < count; ++b) masks[b] = intersectBlock(blocks[b], ray_, &c[b]);
    stats_->leaves += count;
    for (int b = 0; b < count; ++b) {
      stats_->evaluations += std::popcount(masks[b]);
      for (uint32_t mask = masks[b]; mask; mask &= mask - 1) {
        int i = std::countr_zero(mask);
        // The rest of evaluateGaussian, in float.
        BufferedHit h;
        h.id = blocks[b].id[i];
        h.tPeak = c[b].tPeak[i];
        h.tEnter = h.tPeak - c[b].half[i];
        h.tExit = h.tPeak + c[b].half[i];
        h.key = std::clamp(h.tPeak, std::max(h.tEnter, ray_.tMin), h.tExit);
        h.response = response(c[b].r2[i]);
        h.alpha = kMaxAlpha * blocks[b].opacity[i] * h.response;
        if (h.alpha < settings_.alphaMin) continue;
        for (int a = 0; a < 3; ++a) h.localPoint[a] = c[b].localPoint[a][i];
        HitOrder order = h.order();
        if ((hasLo_ && order < lo_) || (hasHi_ && !(order < hi_))) continue;
        if (!accept(h, bound)) return false;
      }
    }
    return true;
  }

  // gaussianResponse in float; small integer powers (1 and 3 are the common ones) as
  // products, within an ulp or two of powf and several times faster.
  float response(float r2) const {
    float power = settings_.kernelPower;
    float r2p;
    switch (integerPower_) {
      case 1: r2p = r2; break;
      case 2: r2p = r2 * r2; break;
      case 3: r2p = r2 * r2 * r2; break;
      case 4: r2p = (r2 * r2) * (r2 * r2); break;
      default: return gaussianResponse(r2, power);
    }
    return std::exp(-r2p / (2.0f * power));
  }

  bool accept(const BufferedHit& h, float bound) {
    if (tail_) {
      compositor_.add(h.id, h.kernelHit());
      return true;
    }
    if (buffer_.full()) {
      // Make room with the hits that are already safe to composite...
      if (!compositeBelow(bound)) return false;
      if (tail_) {
        compositor_.add(h.id, h.kernelHit());
        return true;
      }
      // ...else keep the nearest ones and leave the rest (and everything beyond) to
      // the next pass.
      if (buffer_.full()) {
        hi_ = buffer_.shrink(capacity_ - std::max(1, capacity_ / 4));
        hasHi_ = hiLowered_ = true;
        if (!(h.order() < hi_)) return true;
      }
    }
    // The compositor will read the Gaussian's attributes: start fetching them now.
    const GaussianScene& scene = *bvh_.scene();
    __builtin_prefetch(&scene.diffuse[h.id]);
    __builtin_prefetch(&scene.normal[h.id]);
    __builtin_prefetch(&scene.roughness[h.id]);
    __builtin_prefetch(&scene.f0[h.id]);
    buffer_.push(h);
    return true;
  }

  // Composites, in order, the buffered hits whose key is below `bound`. Returns false
  // when the ray terminated and the exact tail is not wanted; with the exact tail, the
  // remaining hits then only multiply into the final transmittance, in any order.
  bool compositeBelow(float bound) {
    while (!buffer_.empty() && buffer_.nearest().key < bound) {
      BufferedHit h = buffer_.popNearest();
      if (compositor_.add(h.id, h.kernelHit())) continue;
      if (!settings_.exactTail) return false;
      tail_ = true;
      for (int i = 0; i < buffer_.size(); ++i) compositor_.add(buffer_[i].id, buffer_[i].kernelHit());
      buffer_.clear();
    }
    return true;
  }

  const Bvh8& bvh_;
  const TraceSettings& settings_;
  Bvh8Ray ray_;
  Compositor<double> compositor_;
  HitBuffer<FastGaussianTracer::kMaxHitBufferCapacity> buffer_;
  int capacity_;
  int integerPower_;  // kernelPower when it is 1, 2, 3 or 4, else 0
  FastTraceStats* stats_;
  Pending pending_;
  HitOrder lo_{}, hi_{};
  bool hasLo_ = false, hasHi_ = false, hiLowered_ = false;
  bool tail_ = false;  // terminated: later hits only count towards the exact tail
};

}  // namespace

FastGaussianTracer::FastGaussianTracer(int hitBufferCapacity) : hitBufferCapacity_(hitBufferCapacity) {
  GLINT_CHECK(hitBufferCapacity >= 2 && hitBufferCapacity <= kMaxHitBufferCapacity,
              "FastGaussianTracer: hit buffer capacity must be in [2, 256]");
}

void FastGaussianTracer::build(const GaussianScene& scene, const TraceSettings& settings) {
  bvh_.build(scene, settings);
  GLINT_CHECK(kBvhWidth + bvh_.maxStackSize() <= kStackCapacity, "BVH deeper than the traversal stack allows");
  built_ = true;
}

void FastGaussianTracer::refit() {
  GLINT_CHECK(built_, "refit before build");
  bvh_.refit();
  GLINT_CHECK(kBvhWidth + bvh_.maxStackSize() <= kStackCapacity, "BVH deeper than the traversal stack allows");
}

RayResult FastGaussianTracer::trace(const TraceRay& ray, HitList* hits) const {
  FastTraceStats stats;
  return trace(ray, hits, &stats);
}

RayResult FastGaussianTracer::trace(const TraceRay& ray, HitList* hits, FastTraceStats* stats) const {
  GLINT_CHECK(built_, "trace before build");
  RayTraversal traversal(bvh_, ray, hitBufferCapacity_, hits, stats);
  return traversal.run();
}

}  // namespace glint
