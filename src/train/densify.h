// Densification by splitting (3DGS's split, without cloning): where the losses keep pulling a
// Gaussian's position and normal in directions its size cannot follow (highlight edges,
// glossy floors whose normals vary within one Gaussian), the Gaussian becomes two smaller
// ones along its longest axis. The paper does not densify (its dense initialisation has 45x
// our pixels to draw from); this is the lever of issue 22 for our resolution.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "raytrace/gaussian_gradients.h"
#include "scene/gaussians.h"

namespace glint {

struct DensifySettings {
  // Share of the Gaussians split at each densification step (the highest scores); 0 = off.
  // 0.1 from step 1500 to 5000 (8 steps), against none, on the two Blender validation scenes
  // (README): +1.5 and +0.7 dB diffuse, +0.5 and +0.5 specular, +0.7 and +0.55 final; on
  // mirror_room, timed like for like, training took 33:43 against 35:23.
  float fraction = 0.1f;
  int every = 500;   // steps between densification steps (a multiple of prune.every keeps
                     // the children's pruning interval whole)
  int start = 1500;  // first step that densifies (after the first prune, which removes most
                     // of the far field: splitting before it would split what it removes)
  int stop = 5000;   // last step that may densify
  int64_t maxGaussians = 2'000'000;  // no split takes the scene beyond this
};

// Throws Error(where, ...) for settings out of range.
void checkDensifySettings(const DensifySettings& s, const std::string& where);

// The split score of one hit's gradient, splitScore, is in raytrace/gaussian_gradients.h
// (the backward pass sums it on the CPU and on the GPU).

// The indices of the Gaussians to split: the ceil(fraction x n) highest positive scores, at
// most `room` of them, in increasing index order; ties go to the lower index, so the choice
// is deterministic.
std::vector<uint32_t> chooseSplits(std::span<const float> score, float fraction, size_t room);

// Splits each parent into two children at +-half its largest standard deviation along that
// axis, each with every standard deviation divided by 1.6 (3DGS's factor) and the parent's
// other attributes. The first child replaces the parent in place; the second is appended,
// in the order of `parents`.
void splitGaussians(GaussianScene* scene, std::span<const uint32_t> parents);

}  // namespace glint
