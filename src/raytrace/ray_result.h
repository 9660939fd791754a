// What tracing one ray through the Gaussians produces, and the per-ray list of composited
// hits the fused backward pass replays.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vec.h"

namespace glint {

// Blended attributes of one ray (weights w_i = T_i alpha_i, front to back).
struct RayResult {
  Rgb diffuse;            // sum w_i c_i
  float depth = 0;        // sum w_i t_i (expected termination distance along the ray)
  Vec3f normal;           // sum w_i n_i, unnormalised
  float normalLength = 0; // |normal| before normalisation (the paper's validity test)
  float roughness = 0;
  Rgb f0;
  float transmittance = 1;  // T after the composited hits (exact final T with exactTail)
  int hitCount = 0;         // hits composited
  bool truncated = false;   // stopped at minTransmittance
};

// One composited hit: exactly what the backward pass reads (it re-evaluates the kernel for
// the rest), so that the hit lists of a whole training batch stay small.
struct HitRecord {
  uint32_t id;  // Gaussian index
  float t;      // sort key: peak distance clamped into the proxy's entry/exit interval
  float alpha;  // kMaxAlpha * opacity * response
};

// A bounded list of the hits of one ray. Tracers never grow it past `capacity`; when a
// ray needs more, they continue from the last composited hit (never a wrong pixel).
struct HitList {
  std::vector<HitRecord> hits;
  size_t capacity = 512;
  bool overflowed = false;  // the ray had more composited hits than capacity

  void clear() {
    hits.clear();
    overflowed = false;
  }
};

}  // namespace glint
