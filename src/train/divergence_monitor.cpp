// Divergence checks of a training run: non-finite numbers, rays that hit nothing, a loss
// grown by orders of magnitude.
#include "train/divergence_monitor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/parallel.h"
#include "scene/gaussian_parameters.h"

namespace glint {

namespace {

// The label of the first parameter (in table order) of Gaussian i with a non-finite
// component, or nullptr.
const char* nonFiniteParameterOf(const GaussianScene& s, size_t i) {
  const char* label = nullptr;
  forEachParameter([&](const auto& p) {
    for (int k = 0; k < p.components && !label; ++k)
      if (!std::isfinite(component((s.*p.values)[i], k))) label = p.label;
  });
  return label;
}

std::string formatLoss(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

}  // namespace

std::optional<NonFiniteParameter> findNonFiniteParameter(const GaussianScene& scene) {
  // The lowest index over all chunks, so that the answer does not depend on thread timing.
  std::atomic<size_t> first{scene.size()};
  parallelForChunks(int64_t(scene.size()), 16384, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end && size_t(i) < first.load(std::memory_order_relaxed); ++i)
      if (nonFiniteParameterOf(scene, size_t(i))) {
        size_t seen = first.load();
        while (size_t(i) < seen && !first.compare_exchange_weak(seen, size_t(i))) {
        }
        return;
      }
  });
  if (first == scene.size()) return std::nullopt;
  return NonFiniteParameter{first, nonFiniteParameterOf(scene, first)};
}

float medianLargestScale(const GaussianScene& scene, size_t samples) {
  const size_t n = scene.size();
  if (n == 0) return 0.0f;
  const size_t stride = std::max<size_t>(1, n / samples);
  std::vector<float> largest;
  for (size_t i = 0; i < n; i += stride) {
    const Vec3f& s = scene.logScale[i];
    largest.push_back(std::max({s.x, s.y, s.z}));
  }
  auto middle = largest.begin() + ptrdiff_t(largest.size() / 2);
  std::nth_element(largest.begin(), middle, largest.end());
  return std::exp(*middle);
}

std::optional<std::string> DivergenceMonitor::check(const StepReport& report, const GaussianScene& scene) {
  const std::string at = "at step " + std::to_string(report.step) + ": ";
  if (!std::isfinite(report.loss))
    return at + "the loss is " + formatLoss(report.loss) + " (a gradient or parameter overflowed)";
  if (std::optional<NonFiniteParameter> bad = findNonFiniteParameter(scene))
    return at + "Gaussian " + std::to_string(bad->gaussian) + " has a non-finite " + bad->name;
  if (const float median = medianLargestScale(scene); median > kScaleExplosion * sceneExtent_)
    return at + "the scales have exploded: half the Gaussians are larger than " + formatLoss(median) +
           ", over " + formatLoss(kScaleExplosion) + " times the scene's radius (" + formatLoss(sceneExtent_) + ")";

  if (report.rays > 0 && report.hits == 0) {
    if (stepsWithoutHits_++ == 0) firstStepWithoutHits_ = report.step;
  } else {
    stepsWithoutHits_ = 0;
  }
  if (stepsWithoutHits_ >= kSustainedSteps)
    return "from step " + std::to_string(firstStepWithoutHits_) + " to " + std::to_string(report.step) +
           ", no ray hit any Gaussian (the Gaussians have collapsed, vanished or flown off)";

  if (haveLoss_ && report.loss > kLossGrowth * std::max(lowestLoss_, 1e-9)) {
    if (stepsLossHigh_++ == 0) firstStepLossHigh_ = report.step;
  } else {
    stepsLossHigh_ = 0;
  }
  if (stepsLossHigh_ >= kSustainedSteps)
    return "from step " + std::to_string(firstStepLossHigh_) + " to " + std::to_string(report.step) +
           ", the loss stayed above " + formatLoss(kLossGrowth) + " times its lowest (" + formatLoss(lowestLoss_) +
           "; now " + formatLoss(report.loss) + ")";
  lowestLoss_ = haveLoss_ ? std::min(lowestLoss_, report.loss) : report.loss;
  haveLoss_ = true;
  return std::nullopt;
}

}  // namespace glint
