// The GPU's warp-wide walk of the 8-wide BVH: the 32 rays of a warp walk the tree together
// with one stack in shared memory, visiting a node when any of them still needs it, so the
// walk itself never diverges and each node is read once per warp. What a ray does at a
// node, at a leaf and at the end of a pass is KBufferRay's (raytrace/fast/kbuffer_traversal.h),
// as in the per-ray walk: the two give the same hits in the same order.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "raytrace/fast/kbuffer_traversal.h"

namespace glint::cuda {

// One warp's stack: the subtrees still to visit; for each, the rays that wanted it (a bit
// per lane) and the least of their entry distances.
struct WarpStack {
  int32_t code[kKBufferStackCapacity];
  float nearest[kKBufferStackCapacity];
  uint32_t wanters[kKBufferStackCapacity];
};

// Traces traceRay (when `active`) together with the other rays of the warp. All 32 threads
// of the warp must call it (threads without a ray pass active = false): kernels that use it
// launch whole warps and return early from none; `stack` is the warp's own.
template <int K, typename Recorder>
__device__ RayResult traceKBufferWarp(const Bvh8View& bvh, const GaussianAttributes& attributes,
                                      const TraceSettings& settings, const TraceRay& traceRay, bool active,
                                      Recorder recorder, WarpStack& stack) {
  // The whole warp, named explicitly: __activemask() could miss lanes that have not yet
  // reconverged after a branch before the call.
  const unsigned warp = 0xffffffffu;
  const int leader = 0;
  const unsigned laneBit = 1u << (threadIdx.x & 31u);
  KBufferRay<K, Recorder> ray(attributes, settings, traceRay, recorder);
  if (bvh.empty) return ray.finish();
  bool done = !active;
  for (;;) {
    const unsigned walking = __ballot_sync(warp, !done);
    if (walking == 0) break;
    if (!done) ray.startPass();
    if (int(threadIdx.x & 31u) == leader) stack.code[0] = 0, stack.nearest[0] = 0.0f, stack.wanters[0] = walking;
    int top = 1;
    __syncwarp(warp);
    while (top > 0) {
      --top;
      const int32_t code = stack.code[top];
      const float nearest = stack.nearest[top];
      const uint32_t wanters = stack.wanters[top];
      __syncwarp(warp);  // every lane has read the entry before the leader overwrites it
      // A ray visits what it wanted when pushed, unless it may now skip it: its own entry
      // distance is at least `nearest`, so what skips `nearest` skips it (and loses its
      // hits exactly when the per-ray walk would).
      const bool wants = !done && (wanters & laneBit) && !ray.skips(nearest);
      if (!__any_sync(warp, wants)) continue;
      if (Bvh8Node::isLeaf(code)) {
        if (wants) ray.visitLeaf(bvh, code);
        __syncwarp(warp);
        continue;
      }
      const Bvh8Node& node = bvh.nodes[code];
      float tNear[kBvhWidth];
      const uint32_t keep = wants ? ray.children(node, tNear) : 0u;
      // The children any ray keeps, each with the rays that keep it and the least of their
      // entry distances. Entry distances are at least tMin >= 0 (adding 0 turns -0 into +0),
      // so their bits order as unsigned integers.
      float childNearest[kBvhWidth];
      uint32_t childWanters[kBvhWidth];
      uint32_t wanted = 0;
      const unsigned none = 0x7f800000u;  // the bits of +infinity
#pragma unroll
      for (int c = 0; c < kBvhWidth; ++c) {
        const bool mine = keep >> c & 1u;
        childWanters[c] = __ballot_sync(warp, mine);
        childNearest[c] = __uint_as_float(__reduce_min_sync(warp, mine ? __float_as_uint(tNear[c] + 0.0f) : none));
        if (childWanters[c] != 0) wanted |= 1u << c;
      }
      if (top + kBvhWidth > kKBufferStackCapacity) wanted = 0;  // never: callers check the depth bound
      if (int(threadIdx.x & 31u) == leader) {
#pragma unroll
        for (int c = 0; c < kBvhWidth; ++c) {
          if (!(wanted >> c & 1u)) continue;
          const int slot = top + farthestFirstRank(wanted, childNearest, c);
          stack.code[slot] = node.child[c];
          stack.nearest[slot] = childNearest[c];
          stack.wanters[slot] = childWanters[c];
        }
      }
      top += __popc(wanted);
      __syncwarp(warp);
    }
    if (!done) done = ray.finishPass();
  }
  return ray.finish();
}

}  // namespace glint::cuda
