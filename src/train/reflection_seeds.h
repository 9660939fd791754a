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
// normal, roughness or specular buffers this reads). Training pixels whose true surface is
// near-mirror (roughness below s.reflectionSeedRoughness) are taken at an even stride; each
// ray is reflected about the true normal at the true surface point and traced through
// `tracer` (the warm-up's scene), which ends its free segment (or 3 sceneRadius does).
// Where the pixel's specular buffer implies a radiance (specular / Fresnel) that the scene
// does not show there, the reflection stops in the first photo-consistent cell along its
// free segment: a cell that at least three views' reflections cross with the same colour,
// as a surface seen in mirrors from several places is, and empty space (which shows each
// view what lies behind it) is not (voxel colouring). One seed per such cell, at the mean
// point and radiance of the reflections that stopped in it. Seeds that any training view
// sees in front of its recorded surface are removed (carveObservedFreeSpace), so that only
// unobserved space is filled. Each seed otherwise has the far-field attributes (normal 0:
// paths end there). Deterministic in `seed`.
GaussianScene reflectionSeeds(const FarFieldSettings& s, const TrainingViews& views, const GaussianTracer& tracer,
                              const TraceSettings& trace, float backfaceSkip, float sceneRadius, uint64_t seed);

}  // namespace glint
