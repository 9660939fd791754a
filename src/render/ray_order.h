// The order in which a wavefront traces its reflected rays, for the CPU and the GPU: rays
// traced one after the other should start close together and point into the same octant,
// so that they walk the same BVH nodes while those are in the cache.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/cpu_gpu.h"
#include "math/morton.h"
#include "math/vec.h"

namespace glint {

// The sort key of a ray: its direction's octant, then the Morton code of its origin in the
// box [lo, lo + extent] (extent > 0 on every axis; origins outside are clamped to it).
GLINT_CPU_GPU inline uint64_t rayOrderKey(const Vec3f& origin, const Vec3f& direction, const Vec3f& lo,
                                          const Vec3f& extent) {
  uint32_t q[3];
  GLINT_UNROLL
  for (int a = 0; a < 3; ++a) q[a] = uint32_t(std::clamp((origin[a] - lo[a]) / extent[a], 0.0f, 1.0f) * 1023.0f);
  const uint64_t octant =
      uint64_t(direction.x < 0) | uint64_t(direction.y < 0) << 1 | uint64_t(direction.z < 0) << 2;
  return octant << 30 | mortonCode3(q[0], q[1], q[2]);
}

}  // namespace glint
