// L_r, the reflection loss of one recorded path (paper section 3.2, appendix B.5), and its
// gradient into the Gaussians its reflected segments hit.
#pragma once

#include <cstddef>
#include <span>

#include "raytrace/ray_backward.h"
#include "render/gaussian_path.h"
#include "train/ray_loss.h"

namespace glint {

// Specular = sum over the reflected segments k >= 1 of throughput_k x blended diffuse_k
// (equation 3; the first segment carries the diffuse pass).
Rgb pathSpecular(std::span<const PathSegment> segments);

// The weight of segment k's gradient: (1 - rho)^3, rho the roughness of the surface the
// segment leaves (the previous segment's blended roughness, clamped to [0, 1]). It favours
// the low-variance gradients of sharp reflections (appendix B.5).
float reflectionGradientWeight(std::span<const PathSegment> segments, size_t k);

// Back-propagates g = dL/d(specular) through each reflected segment's blended diffuse:
// the colour, opacity, position and shape of the Gaussians the segment hits. Nothing
// flows into normals, roughness or F0, the throughputs or the sampled directions (the
// paper detaches them). Segments whose hit list overflowed get no gradient; returns how
// many did. T = float in training, double for the finite-difference tests.
template <typename T, typename Sink>
int reflectionLoss_vjp(const GaussianScene& scene, const TraceSettings& trace, std::span<const PathSegment> segments,
                       const Rgb& g, RayBackwardScratch<T>& scratch, Sink&& sink) {
  int overflowed = 0;
  for (size_t k = 1; k < segments.size(); ++k) {
    const PathSegment& segment = segments[k];
    if (segment.hits.overflowed) {
      ++overflowed;
      continue;
    }
    RayResultAdjoint v;
    v.v_diffuse = segment.throughput * g * reflectionGradientWeight(segments, k);
    backwardRay<T>(scene, trace, segment.ray, segment.hits, segment.result, v, scratch, sink);
  }
  return overflowed;
}

}  // namespace glint
