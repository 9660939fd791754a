// The result of importance-sampling a BRDF lobe: an incident direction and its weight.
#pragma once

#include "math/vec.h"

namespace glint {

// All directions live in the local shading frame (normal = +z) and point away from the surface.
struct BsdfSample {
  Vec3f wi;        // sampled incident direction
  Rgb weight;      // f(wo, wi) cos(theta_i) / pdf: the path throughput multiplier
  float pdf = 0;   // density of wi with respect to solid angle
  bool valid = false;  // false when no direction was produced (e.g. wi fell below the horizon)
};

}  // namespace glint
