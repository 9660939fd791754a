// Lighting the colour that healing continues into an uncovered surface where it stands, not
// where the surface it was continued from stands.
#pragma once

#include <cstdint>
#include <vector>

#include "edit/heal_uncovered.h"
#include "raytrace/gaussian_tracer.h"
#include "render/differential_relight.h"
#include "scene/gaussians.h"

namespace glint {

// Healing gives each healed Gaussian h its ring's colour, C_h = sum_n w_n C_n; the ring's
// colours hold the light at the ring. This returns, per report.healed entry, the factor
// that moves that light to h:
//
//   E(h) / sum_n w_n E(n)
//
// the irradiance at h over the weighted irradiance at its ring neighbours, both in the edited
// scene (luminance, clamped to [1 / maxRatio, maxRatio]): a healed floor that the moved
// object's new shadow covers comes out as dark as its shadow, not as bright as the open floor
// around it. Every point traces the same cosine-distributed directions in its own frame
// (settings.hemisphereRays x refineFactor of them, with settings.path, minReflectance and
// seed), so a distant light that both see cancels out of the ratio instead of adding its
// noise twice. Each ray counts at least one reflected segment where it meets a metal or
// mirror (settings.path.bounces, at least 1): a healed floor lies next to the object that
// stood there, where the light a chrome object reflects is a large share. Against none, on
// the move and deletion of builtin:spheres, the Blender spheres_room and mirror_room (16 spp,
// diffuse 8-bit dB) it gained 0.09, 0.01, -0.02, -0.03, -0.09 and 0.29 (README, "Healed
// colours lit where they stand"). A point without a normal, or a ring that receives no
// light, gives 1. Adds the segments traced to *rays. Throws RelightCancelled when
// settings.cancel turns true.
std::vector<float> healedLightFactors(const GaussianTracer& after, const GaussianScene& afterScene,
                                      const HealReport& report, const RelightSettings& settings, uint64_t* rays);

}  // namespace glint
