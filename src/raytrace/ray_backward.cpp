// The hit-list capacity bound of the backward pass.
#include "raytrace/ray_backward.h"

#include <algorithm>
#include <cmath>

namespace glint {

size_t hitCapacityWithoutOverflow(const TraceSettings& s) {
  double keep = 1.0 - std::clamp(double(s.alphaMin), 1e-6, 0.999);
  double minT = std::max(double(s.minTransmittance), 1e-12);
  return size_t(std::ceil(std::log(minT) / std::log(keep))) + 2;
}

}  // namespace glint
