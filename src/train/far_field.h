// Far-field Gaussians (paper section 3.3 and appendix B): a cloud of coarse Gaussians added
// when reflections start, so that reflected rays find something to reconstruct the parts
// of the environment no training camera sees directly (the ceiling light, walls behind
// the cameras, the sky).
#pragma once

#include <cstdint>
#include <string>

#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

struct FarFieldSettings {
  int count = 75000;          // M; 0 adds none
  float sigmaFactor = 4.0f;   // positions ~ N(centre, (sigmaFactor x S)^2) per axis
  float truncation = 3.0f;    // ... truncated at this many sigma from the centre
  float opacity = 0.1f;
  float diffuse = 0.2f;
  int neighbours = 3;         // initial scale = mean distance to this many nearest far-field points
};

// Throws Error(where, ...) for settings out of range.
void checkFarFieldSettings(const FarFieldSettings& s, const std::string& where);

// M Gaussians around `centre` at the scale S = `sceneRadius` (3DGS's camera-sphere radius):
// positions from a normal distribution truncated by rejection to `truncation` sigma;
// isotropic scales from the nearest-neighbour distances of the cloud (as the dense
// initialisation sizes its points); normal 0, so paths reaching them end; roughness 0
// and F0 0.04 as the other initial Gaussians. Deterministic in `seed`.
GaussianScene farFieldGaussians(const FarFieldSettings& s, const Vec3f& centre, float sceneRadius, uint64_t seed);

}  // namespace glint
