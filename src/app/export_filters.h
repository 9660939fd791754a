// Which Gaussians `glint export` keeps: the far-field cut around the training cameras and
// the --crop box. Nothing in a scene marks its far-field Gaussians (train/far_field.h adds
// them to the same arrays, and pruning and densification reorder them), so they are told
// apart by where they lie.
#pragma once

#include <vector>

#include "eval/region_metrics.h"
#include "math/vec.h"
#include "scene/gaussians.h"
#include "train/scene_extent.h"

namespace glint {

// The far-field cloud is drawn around the training cameras' centre with a standard
// deviation of 4 S (S = the camera sphere's radius, train/scene_extent.h), truncated at
// 12 S. Five S keeps the builtin rooms whole (their farthest corners lie 3.9 S from the
// training cameras' centre in builtin:room, 2.0 S in builtin:gallery, 1.8 S in
// builtin:spheres) and removes about two thirds of the cloud (a chi distribution's tail),
// the part tens of metres out that a splat viewer shows as fog around the scene.
inline constexpr float kDefaultFarFieldRadius = 5.0f;

// True for the Gaussians whose centre lies within radiusFactor x cameras.radius of
// cameras.centre (on the sphere counts as inside).
std::vector<bool> nearTheCameras(const GaussianScene& scene, const SceneSphere& cameras, float radiusFactor);

// True for the Gaussians whose centre lies in the box (faces included).
std::vector<bool> insideBox(const GaussianScene& scene, const WorldBox& box);

// How many entries of a mask are false.
size_t countDropped(const std::vector<bool>& keep);

}  // namespace glint
