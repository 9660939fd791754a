// The per-receiver estimates of differential relighting (dE and E_before, then their ratio)
// for many receivers at once: each step's rays from every receiver still in play are traced
// as one batch through PathBatch, the wavefront the renderer uses, and summed per receiver
// in the order of its sequences, so each ratio is what tracing its rays one by one gives.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/progress.h"
#include "raytrace/gaussian_tracer.h"
#include "render/differential_relight.h"
#include "render/light_regions.h"
#include "scene/gaussians.h"

namespace glint {

struct RatioCounts {
  size_t changed = 0;  // receivers whose ratio is not 1
  size_t clamped = 0;  // ... that hit the clamp in some channel
  uint64_t rays = 0;   // segments traced, both scenes together
};

// Sets (*ratios)[i] = E_after / E_before for every i of `traced` (indices into `receivers`,
// Gaussians of afterScene within reach of the changed regions), as relightRatios describes,
// and leaves the other entries alone. Advances `progress` by one per receiver. Stops early
// when settings.cancel turns true (the caller throws RelightCancelled).
RatioCounts traceIrradianceRatios(const GaussianTracer& before, const GaussianTracer& after,
                                  const GaussianScene& afterScene, std::span<const uint32_t> receivers,
                                  std::span<const uint32_t> traced, std::span<const ChangedRegion> regions,
                                  std::span<const LightRegion> lights, const RelightSettings& settings,
                                  std::vector<Rgb>* ratios, ProgressBar* progress);

}  // namespace glint
