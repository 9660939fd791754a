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
#include "math/fast_exp.h"
#include "raytrace/compositor.h"
#include "raytrace/fast/bvh8_kernels.h"
#include "raytrace/fast/hit_buffer.h"
#include "raytrace/fast/kernel_response.h"
#include "raytrace/fast/pending_subtrees.h"
#include "raytrace/fast/ray_bundle.h"
#include "core/parallel.h"

namespace glint {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Pending subtrees ordered by entry distance; more overflow into a depth-first stack,
// which the tree's bounded depth keeps within kStackCapacity (checked at build).
constexpr int kHeapCapacity = 256;
constexpr int kStackCapacity = 512;
using Pending = PendingSubtrees<kHeapCapacity, kStackCapacity>;

// Turns the lanes of a tested leaf block into hits: the rest of evaluateGaussian, in float.
class LaneHits {
 public:
  explicit LaneHits(const TraceSettings& settings) : settings_(settings), response_(settings.kernelPower) {}

  // Lane i of `block` (whose proxy test passed, giving c); false when its alpha is below alphaMin.
  bool make(const Bvh8Block& block, const Bvh8BlockCandidates& c, int i, float tMin, KeyedHit* h) const {
    return makeLaneHit(response_, settings_.alphaMin, block, i, c, i, tMin, h);
  }

  // The alphas of the lanes of c (one Gaussian of the given opacity against a packet of
  // rays), bit for bit those of make; returns the lanes of `mask` whose alpha reaches
  // alphaMin. All 8 lanes at once for the integer powers.
  uint32_t alphas(const Bvh8BlockCandidates& c, uint32_t mask, float opacity, float alpha[kBvhWidth]) const {
#ifdef __AVX2__
    if (const int power = response_.integerPower(); power != 0) {
      __m256 r2 = _mm256_load_ps(c.r2);
      __m256 r2p = r2;
      if (power == 2) r2p = _mm256_mul_ps(r2, r2);
      if (power == 3) r2p = _mm256_mul_ps(_mm256_mul_ps(r2, r2), r2);
      if (power == 4) r2p = _mm256_mul_ps(_mm256_mul_ps(r2, r2), _mm256_mul_ps(r2, r2));
      __m256 g = expNonPositiveAvx2(_mm256_mul_ps(r2p, _mm256_set1_ps(response_.exponentScale())));
      __m256 a = _mm256_mul_ps(_mm256_set1_ps(kMaxAlpha * opacity), g);
      _mm256_store_ps(alpha, a);
      return mask & uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(a, _mm256_set1_ps(settings_.alphaMin), _CMP_GE_OQ)));
    }
#endif
    uint32_t passing = 0;
    for (uint32_t m = mask; m; m &= m - 1) {
      int i = std::countr_zero(m);
      alpha[i] = response_.alpha(opacity, c.r2[i]);
      passing |= uint32_t(!(alpha[i] < settings_.alphaMin)) << i;
    }
    return passing;
  }

  // The sort key of lane i: the peak clamped into the proxy's chord beyond tMin.
  static float key(const Bvh8BlockCandidates& c, int i, float tMin) {
    return hitKey(c.tPeak[i], c.tPeak[i] - c.half[i], c.tPeak[i] + c.half[i], tMin);
  }

 private:
  const TraceSettings& settings_;
  KernelResponse response_;
};

using FastHitBuffer = HitBuffer<FastGaussianTracer::kMaxHitBufferCapacity>;
using FastCompositor = Compositor<float>;

// Composites, in order, the buffered hits whose key is below `bound`. Returns false when
// the ray terminated and the exact tail is not wanted; with the exact tail, the remaining
// hits then only multiply into the final transmittance, in any order (*tail is set).
template <typename Buffer>
bool compositeBelow(float bound, Buffer& buffer, FastCompositor& compositor,
                    const TraceSettings& settings, bool* tail) {
  while (!buffer.empty() && buffer.nearest().key < bound) {
    auto h = buffer.popNearest();
    if (compositor.add(h.id, h.kernelHit())) continue;
    if (!settings.exactTail) return false;
    *tail = true;
    for (int i = 0; i < buffer.size(); ++i) compositor.add(buffer[i].id, buffer[i].kernelHit());
    buffer.clear();
  }
  return true;
}

// The compositor will read the Gaussian's attributes: start fetching them now.
void prefetchAttributes(const GaussianScene& scene, uint32_t id) {
  __builtin_prefetch(&scene.diffuse[id]);
  __builtin_prefetch(&scene.normal[id]);
  __builtin_prefetch(&scene.roughness[id]);
  __builtin_prefetch(&scene.f0[id]);
}

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
        lanes_(bvh.settings()),
        stats_(stats) {
    if (ray.backfaceSkip > 0) compositor_.skipBackfacing(ray.direction, ray.backfaceSkip);
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
        KeyedHit h;
        if (!lanes_.make(blocks[b], c[b], i, ray_.tMin, &h)) continue;
        HitOrder order = h.order();
        if ((hasLo_ && order < lo_) || (hasHi_ && !(order < hi_))) continue;
        if (!accept(h, bound)) return false;
      }
    }
    return true;
  }

  bool accept(const KeyedHit& h, float bound) {
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
    prefetchAttributes(*bvh_.scene(), h.id);
    buffer_.push(h);
    return true;
  }

  bool compositeBelow(float bound) { return glint::compositeBelow(bound, buffer_, compositor_, settings_, &tail_); }

  const Bvh8& bvh_;
  const TraceSettings& settings_;
  Bvh8Ray ray_;
  FastCompositor compositor_;
  FastHitBuffer buffer_;
  int capacity_;
  LaneHits lanes_;
  FastTraceStats* stats_;
  Pending pending_;
  HitOrder lo_{}, hi_{};
  bool hasLo_ = false, hasHi_ = false, hiLowered_ = false;
  bool tail_ = false;  // terminated: later hits only count towards the exact tail
};

// The rays of one bundle, traced chunk by chunk through the bundle's candidates (in the
// order of the lower bound of their keys). The loop runs over Gaussians, not rays: all rays
// share the origin, so each candidate is tested against the packets of 8 rays whose cone
// its bounding sphere meets, 8 rays per test, and its hits go to those rays' buffers.
// Before every 64 candidates each ray composites its buffered hits below their bound, so
// the order is the exact (key, id) order of RayTraversal. Chunks are gathered only while
// some ray is still compositing. A ray whose hit buffer overflows is handed back; the
// caller traces it alone, and that traversal handles overflow.
class BundleStreams {
 public:
  // Traces rays[members] and writes results[members] (and hits[members] when hits is not
  // empty); appends the overflowed rays to *overflowed (their results are left for the caller).
  void trace(const Bvh8& bvh, BundleCandidates& candidates, const RayCone& cone, std::span<const TraceRay> rays,
             std::span<const uint32_t> members, int capacity, std::span<RayResult> results, std::span<HitList> hits,
             std::vector<uint32_t>* overflowed) {
    const TraceSettings& settings = bvh.settings();
    const size_t n = members.size();
    if (buffers_.size() < n) buffers_.resize(n, FastHitBuffer(capacity));
    compositors_.clear();
    compositors_.reserve(n);
    states_.assign(n, Streaming);
    tails_.assign(n, false);
    for (size_t k = 0; k < n; ++k) {
      const TraceRay& ray = rays[members[k]];
      buffers_[k].reset(capacity);
      compositors_.emplace_back(*bvh.scene(), settings, hits.empty() ? nullptr : &hits[members[k]]);
      if (ray.backfaceSkip > 0) compositors_[k].skipBackfacing(ray.direction, ray.backfaceSkip);
    }
    makePackets(cone, rays, members);
    const LaneHits lanes(settings);
    candidates.start(bvh, cone);
    // Small first chunks suit bundles that terminate in the first surface; doubling keeps
    // the number of chunks logarithmic for those that see deep into the cloud.
    for (size_t chunk = kFirstChunk; streaming_ > 0 && candidates.next(chunk); chunk *= 2) {
      streamChunk(settings, candidates, lanes, *bvh.scene());
      // Nothing of the later chunks comes before the frontier.
      compositeStreaming(settings, candidates.frontier());
    }
    for (size_t k = 0; k < n; ++k) {
      if (states_[k] == Overflowed) {
        overflowed->push_back(members[k]);
        continue;
      }
      bool tail = tails_[k];
      if (states_[k] == Streaming && !tail)
        compositeBelow(kInfinity, buffers_[k], compositors_[k], settings, &tail);
      results[members[k]] = compositors_[k].finish();
    }
  }

 private:
  enum State : uint8_t { Streaming, Terminated, Overflowed };
  static constexpr size_t kFirstChunk = 256;

  // Packs the rays 8 to a packet (the last one padded with copies of its first ray, never
  // active) and bounds each packet by a cone; all rays start streaming.
  void makePackets(const RayCone& cone, std::span<const TraceRay> rays, std::span<const uint32_t> members) {
    const size_t n = members.size(), packetCount = (n + kBvhWidth - 1) / kBvhWidth;
    origin_ = cone.apex;
    packets_.resize(packetCount);
    active_.assign(packetCount, 0);
    cones_.resize((packetCount + kBvhWidth - 1) / kBvhWidth);
    activePackets_.assign(cones_.size(), 0);
    for (size_t p = 0; p < packetCount; ++p) {
      std::span<const uint32_t> packetRays = members.subspan(p * kBvhWidth, std::min<size_t>(kBvhWidth, n - p * kBvhWidth));
      for (int i = 0; i < kBvhWidth; ++i) {
        // The per-ray test's constants, so both tests see the same direction bit for bit.
        Bvh8Ray ray(rays[packetRays[size_t(i) < packetRays.size() ? size_t(i) : 0]]);
        for (int a = 0; a < 3; ++a) packets_[p].direction[a][i] = ray.direction[a];
        packets_[p].tMin[i] = ray.tMin;
      }
      active_[p] = uint8_t((1u << packetRays.size()) - 1);
      activePackets_[p / kBvhWidth] |= 1u << (p % kBvhWidth);
      // A packet of a bundle lies in the bundle's cone; its own is usually much narrower.
      RayCone packetCone;
      if (!boundingCone(rays, packetRays, &packetCone)) packetCone = cone;
      PacketCones& group = cones_[p / kBvhWidth];
      int lane = int(p % kBvhWidth);
      for (int a = 0; a < 3; ++a) group.axis[a][lane] = packetCone.axis[a];
      group.cosAngle[lane] = packetCone.cosAngle;
      group.sinAngle[lane] = packetCone.sinAngle;
    }
    streaming_ = n;
  }

  // Ray k of packet p stops streaming in state s.
  void stop(size_t p, int i, State s) {
    states_[p * kBvhWidth + size_t(i)] = s;
    active_[p] &= uint8_t(~(1u << i));
    if (active_[p] == 0) activePackets_[p / kBvhWidth] &= ~(1u << (p % kBvhWidth));
    --streaming_;
  }

  // Every streaming ray composites its buffered hits below `bound`.
  void compositeStreaming(const TraceSettings& settings, float bound) {
    for (size_t p = 0; p < packets_.size(); ++p)
      for (uint32_t rays = active_[p]; rays; rays &= rays - 1) {
        int i = std::countr_zero(rays);
        size_t k = p * kBvhWidth + size_t(i);
        if (tails_[k] || buffers_[k].empty()) continue;
        bool tail = false;
        if (!compositeBelow(bound, buffers_[k], compositors_[k], settings, &tail)) stop(p, i, Terminated);
        if (tail) tails_[k] = true;
      }
  }

  // Tests every candidate of the chunk against the packets its bounding sphere meets.
  void streamChunk(const TraceSettings& settings, const BundleCandidates& candidates, const LaneHits& lanes,
                   const GaussianScene& scene) {
    for (int b = 0; b < candidates.blockCount() && streaming_ > 0; ++b) {
      // Every hit of this block and the later ones has a key of at least the bound.
      if (b % kBvhWidth == 0) compositeStreaming(settings, candidates.blockBound(b));
      const Bvh8Block& block = candidates.block(b);
      for (int g = 0; g < kBvhWidth; ++g) {
        if (!(block.radius2[g] >= 0.0f)) continue;  // an empty lane
        Vec3f mean(block.mean[0][g], block.mean[1][g], block.mean[2][g]);
        for (size_t group = 0; group < cones_.size(); ++group) {
          uint32_t packets = activePackets_[group];
          if (packets) packets &= conesMeetingSphere(cones_[group], origin_, mean, block.boundRadius[g]);
          for (; packets; packets &= packets - 1) {
            size_t p = group * kBvhWidth + size_t(std::countr_zero(packets));
            Bvh8BlockCandidates c;
            uint32_t rays = intersectPacket(block, g, &origin_.x, packets_[p], &c) & active_[p];
            if (!rays) continue;
            alignas(32) float alpha[kBvhWidth];
            for (rays = lanes.alphas(c, rays, block.opacity[g], alpha); rays; rays &= rays - 1) {
              int i = std::countr_zero(rays);
              KeyedHit h{LaneHits::key(c, i, packets_[p].tMin[i]), block.id[g], alpha[i]};
              size_t k = p * kBvhWidth + size_t(i);
              if (tails_[k]) {
                compositors_[k].add(h.id, h.kernelHit());
                continue;
              }
              if (buffers_[k].full()) {
                stop(p, i, Overflowed);
                continue;
              }
              prefetchAttributes(scene, h.id);
              buffers_[k].push(h);
            }
          }
        }
      }
    }
  }

  Vec3f origin_;
  std::vector<RayPacket> packets_;
  std::vector<uint8_t> active_;  // per packet: the rays still streaming
  std::vector<PacketCones> cones_;  // cones_[j] lane l: packet 8 j + l
  std::vector<uint32_t> activePackets_;  // per group of cones: the packets with a streaming ray
  size_t streaming_ = 0;
  std::vector<FastHitBuffer> buffers_;
  std::vector<FastCompositor> compositors_;
  std::vector<State> states_;
  std::vector<bool> tails_;
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

size_t FastGaussianTracer::rayScratchBytes() { return sizeof(RayTraversal); }

size_t FastGaussianTracer::bundleScratchBytes() {
  const size_t rays = size_t(kDefaultBundleRays);
  return sizeof(BundleStreams) + rays * (sizeof(FastHitBuffer) + sizeof(FastCompositor) + 2) +
         (rays / kBvhWidth) * (sizeof(RayPacket) + 1) + sizeof(PacketCones);
}

RayResult FastGaussianTracer::trace(const TraceRay& ray, HitList* hits) const {
  FastTraceStats stats;
  return trace(ray, hits, &stats);
}

void FastGaussianTracer::traceBatch(std::span<const TraceRay> rays, std::span<RayResult> results,
                                    std::span<HitList> hits, RayCoherence coherence) const {
  GLINT_CHECK(built_, "trace before build");
  GLINT_CHECK(rays.size() == results.size(), "traceBatch: one result per ray");
  GLINT_CHECK(hits.empty() || hits.size() == rays.size(), "traceBatch: one hit list per ray, or none");
  GLINT_CHECK(rays.size() < size_t(UINT32_MAX), "traceBatch: too many rays");
  auto traceAlone = [&](size_t k) { results[k] = trace(rays[k], hits.empty() ? nullptr : &hits[k]); };
  if (coherence == RayCoherence::Scattered || bundleRays_ < 2) {
    parallelForChunks(int64_t(rays.size()), 64, [&](int64_t begin, int64_t end) {
      for (int64_t k = begin; k < end; ++k) traceAlone(size_t(k));
    });
    return;
  }
  // Runs of consecutive rays with one origin, ordered by direction and cut into bundles;
  // every other ray is traced alone.
  std::vector<uint32_t> order(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) order[i] = uint32_t(i);
  struct Span {
    size_t begin, end;  // into order
  };
  std::vector<Span> bundles;
  std::vector<uint32_t> alone;
  const size_t bundleRays = size_t(bundleRays_);
  for (size_t i = 0; i < rays.size();) {
    size_t j = i + 1;
    const Vec3f& o = rays[i].origin;
    while (j < rays.size() && rays[j].origin.x == o.x && rays[j].origin.y == o.y && rays[j].origin.z == o.z) ++j;
    size_t inside = 0;
    if (j - i >= bundleRays) {
      inside = orderByDirection(rays, std::span<uint32_t>(order).subspan(i, j - i));
      for (size_t b = i; b < i + inside; b += bundleRays) bundles.push_back({b, std::min(b + bundleRays, i + inside)});
    }
    alone.insert(alone.end(), order.begin() + std::ptrdiff_t(i + inside), order.begin() + std::ptrdiff_t(j));
    i = j;
  }

  parallelFor(int64_t(bundles.size()), 1, [&](int64_t b) {
    thread_local BundleCandidates candidates;
    std::span<const uint32_t> members = std::span<const uint32_t>(order).subspan(
        bundles[size_t(b)].begin, bundles[size_t(b)].end - bundles[size_t(b)].begin);
    RayCone cone;
    if (!boundingCone(rays, members, &cone)) {
      for (uint32_t k : members) traceAlone(k);
      return;
    }
    thread_local BundleStreams streams;
    thread_local std::vector<uint32_t> overflowed;
    overflowed.clear();
    streams.trace(bvh_, candidates, cone, rays, members, hitBufferCapacity_, results, hits, &overflowed);
    for (uint32_t k : overflowed) traceAlone(k);
  });
  parallelFor(int64_t(alone.size()), 64, [&](int64_t k) { traceAlone(alone[size_t(k)]); });
}

RayResult FastGaussianTracer::trace(const TraceRay& ray, HitList* hits, FastTraceStats* stats) const {
  GLINT_CHECK(built_, "trace before build");
  RayTraversal traversal(bvh_, ray, hitBufferCapacity_, hits, stats);
  return traversal.run();
}

}  // namespace glint
