// Choosing the Gaussians to split and splitting them.
#include "train/densify.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "math/quat.h"

namespace glint {

void checkDensifySettings(const DensifySettings& s, const std::string& where) {
  if (!(s.fraction >= 0.0f && s.fraction <= 1.0f)) throw Error(where, "densify.fraction must be in [0, 1] (0 = off)");
  if (s.every < 1) throw Error(where, "densify.every must be at least 1");
  if (s.start < 0) throw Error(where, "densify.start must be non-negative");
  if (s.stop < s.start) throw Error(where, "densify.stop must not be before densify.start");
  if (s.maxGaussians < 1) throw Error(where, "densify.max_gaussians must be at least 1");
}

std::vector<uint32_t> chooseSplits(std::span<const float> score, float fraction, size_t room) {
  const size_t wanted = std::min(size_t(std::ceil(double(fraction) * double(score.size()))), room);
  std::vector<uint32_t> order;
  for (size_t i = 0; i < score.size(); ++i)
    if (score[i] > 0.0f) order.push_back(uint32_t(i));  // NaN scores are never chosen
  const size_t count = std::min(wanted, order.size());
  auto higher = [&](uint32_t a, uint32_t b) { return score[a] != score[b] ? score[a] > score[b] : a < b; };
  std::nth_element(order.begin(), order.begin() + std::ptrdiff_t(count), order.end(), higher);
  order.resize(count);
  std::sort(order.begin(), order.end());
  return order;
}

void splitGaussians(GaussianScene* scene, std::span<const uint32_t> parents) {
  constexpr float kShrink = 1.6f;
  const float logShrink = std::log(kShrink);
  for (uint32_t i : parents) {
    GLINT_CHECK(i < scene->size(), "splitGaussians: index out of range");
    const Vec3f logScale = scene->logScale[i];
    int axis = 0;
    if (logScale.y > logScale[axis]) axis = 1;
    if (logScale.z > logScale[axis]) axis = 2;
    const Mat3f rotation = quatToRotation(scene->rotation[i]);
    const Vec3f direction{rotation.m[0][axis], rotation.m[1][axis], rotation.m[2][axis]};
    const Vec3f offset = direction * (0.5f * std::exp(logScale[axis]));
    const Vec3f centre = scene->position[i];
    scene->logScale[i] = logScale - Vec3f(logShrink);
    scene->position[i] = centre - offset;
    scene->append(*scene, i);
    scene->position.back() = centre + offset;
  }
}

}  // namespace glint
