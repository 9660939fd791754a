// Procedural textures with detail at every scale and no repetition, so that feature
// matchers (COLMAP's SIFT) find many distinct keypoints in renders of the built-in scenes.
#pragma once

#include <cstdint>
#include <string>

#include "synth/mesh_scene.h"

namespace glint {

// A "dead leaves" image (Matheron's model of occluding objects; its statistics resemble
// natural images' at every scale): size x size texels of overlapping discs, painted one on
// top of another, with radii from `minRadius` to size/8 texels distributed as 1/r^3 (scale
// invariant), each a random colour with albedo between `darkest` and `brightest`, shaded
// by a gentle gradient so discs are not flat. Deterministic in seed.
Texture makeDeadLeavesTexture(const std::string& name, int size, uint64_t seed, float darkest = 0.08f,
                              float brightest = 0.75f, float minRadius = 1.5f);

}  // namespace glint
