// Renders views of a Gaussian scene through a GaussianTracer: pixel sampling, averaging
// of the per-ray outputs, and the buffers of a view.
#pragma once

#include <cstdint>

#include "raytrace/gaussian_tracer.h"
#include "scene/buffers.h"
#include "scene/camera.h"

namespace glint {

struct RenderSettings {
  int spp = 1;
  // Jittered sub-pixel positions (uniform in the pixel, one stream per pixel); without
  // jitter every sample goes through the pixel centre.
  bool jitter = true;
  uint64_t seed = 0;
};

// Renders render, diffuse, depth, normal, roughness and f0 of one view (specular stays
// zero until reflections exist; render = diffuse). Each buffer averages the spp samples;
// the normal buffer is the average of the blended normals, normalised where non-zero.
ViewBuffers renderGaussianView(const GaussianTracer& tracer, const Camera& camera, const RenderSettings& settings,
                               uint64_t viewKey);

}  // namespace glint
