// The specular sum of a recorded path and the per-segment gradient weight.
#include "train/reflection_loss.h"

#include <algorithm>

namespace glint {

Rgb pathSpecular(std::span<const PathSegment> segments) {
  Rgb specular(0.0f);
  for (size_t k = 1; k < segments.size(); ++k) specular += segments[k].throughput * segments[k].result.diffuse;
  return specular;
}

float reflectionGradientWeight(std::span<const PathSegment> segments, size_t k) {
  float rho = std::clamp(segments[k - 1].result.roughness, 0.0f, 1.0f);
  return (1 - rho) * (1 - rho) * (1 - rho);
}

}  // namespace glint
