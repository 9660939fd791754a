// Where in its pixel a camera ray's sample goes, for the CPU and the GPU.
#pragma once

#include <cstdint>

#include "core/cpu_gpu.h"
#include "math/owen_sobol.h"
#include "math/vec.h"

namespace glint {

// The sub-pixel position of a pixel's sample: dimension 0 of its stratified stream (the
// path's segments use dimensions 1, 2, ...), so a pixel's samples cover it evenly; the
// pixel centre without jitter.
GLINT_CPU_GPU inline Vec2f pixelSampleOffset(bool jitter, uint64_t seed, uint64_t viewKey, uint64_t pixel,
                                             uint32_t sample) {
  if (!jitter) return Vec2f(0.5f, 0.5f);
  return stratifiedSample2(hashKeys({seed, viewKey, pixel, 0}), sample);
}

}  // namespace glint
