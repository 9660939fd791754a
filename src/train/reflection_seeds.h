// Far-field Gaussians seeded along the mirror-reflected rays of training pixels whose
// reflection the scene does not explain yet, kept only in space no training camera sees
// directly: what a mirror shows of the room behind the cameras (an object seen only in
// the mirror), which the far-field cloud of appendix B covers too thinly to reconstruct.
#pragma once

#include <cstdint>

#include "raytrace/gaussian_tracer.h"
#include "scene/gaussians.h"
#include "train/far_field.h"

namespace glint {

class TrainingViews;

// At most s.reflectionSeeds Gaussians (none when 0, or when the views lack the depth,
// normal, roughness or specular buffers this reads). For random training pixels whose
// true surface is near-mirror (roughness below s.reflectionSeedRoughness), the ray is
// reflected about the true normal at the true surface point and traced through `tracer`
// (the warm-up's scene); where what it meets does not match the radiance the pixel's
// specular buffer implies (specular / Fresnel), one seed is placed at a random distance
// along the ray's free segment (before the scene stops it, or up to 3 sceneRadius). Seeds
// that any training view sees in front of its recorded surface are removed
// (carveObservedFreeSpace), so that only unobserved space is filled. Each seed starts with
// that implied radiance as its colour and otherwise the far-field attributes (normal 0:
// paths end there). Deterministic in `seed`.
GaussianScene reflectionSeeds(const FarFieldSettings& s, const TrainingViews& views, const GaussianTracer& tracer,
                              const TraceSettings& trace, float backfaceSkip, float sceneRadius, uint64_t seed);

}  // namespace glint
