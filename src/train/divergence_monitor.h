// Notices a training run that has diverged, so that it stops with a message naming the
// step and the likely cause instead of running on to "done" with a broken scene.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "scene/gaussians.h"
#include "train/trainer.h"

namespace glint {

class DivergenceMonitor {
 public:
  // Rays that hit no Gaussian, or a loss this many times its lowest, for this many steps in
  // a row count as collapse. One step of either happens in healthy runs (a batch of rays
  // through a gap; a noisy batch); twenty in a row do not.
  static constexpr int kSustainedSteps = 20;
  static constexpr double kLossGrowth = 1000.0;
  // Scales explode when the median Gaussian (its largest axis) outgrows the scene this many
  // times. Healthy runs stay far below: scene Gaussians are millimetres to centimetres, and
  // even the far-field cloud, spread over 12 scene radii, is spaced (and sized) at about a
  // third of one.
  static constexpr float kScaleExplosion = 10.0f;

  // sceneExtent: the scene's radius (3DGS camera extent, Trainer::sceneExtent()).
  explicit DivergenceMonitor(float sceneExtent) : sceneExtent_(sceneExtent) {}

  // Looks at a finished step and the scene after it. Returns why the run has diverged, or
  // nothing while it is healthy. Non-finite losses and parameters, and exploded scales,
  // are reported at once.
  std::optional<std::string> check(const StepReport& report, const GaussianScene& scene);

  // False while a collapse may be under way (a sustained condition has begun but not yet
  // lasted kSustainedSteps): checkpoints wait, so that the last one kept is a good one.
  bool clean() const { return stepsWithoutHits_ == 0 && stepsLossHigh_ == 0; }

 private:
  float sceneExtent_;
  double lowestLoss_ = 0;
  bool haveLoss_ = false;
  int stepsWithoutHits_ = 0;
  int stepsLossHigh_ = 0;
  int64_t firstStepWithoutHits_ = 0;
  int64_t firstStepLossHigh_ = 0;
};

// The first Gaussian with a non-finite parameter, and that parameter's name.
struct NonFiniteParameter {
  size_t gaussian = 0;
  const char* name = "";
};
std::optional<NonFiniteParameter> findNonFiniteParameter(const GaussianScene& scene);

// The median over Gaussians of the largest standard deviation, from at most `samples`
// Gaussians evenly spaced by index (deterministic); 0 for an empty scene.
float medianLargestScale(const GaussianScene& scene, size_t samples = 8192);

}  // namespace glint
