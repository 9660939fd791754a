// Adam (Kingma and Ba 2015) over the parameter arrays of a GaussianScene (the parameter
// table's), one learning rate per parameter, with the bias correction of PyTorch's
// implementation (3DGS's).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "raytrace/gaussian_gradients.h"
#include "scene/gaussian_parameters.h"
#include "scene/gaussians.h"
#include "train/train_config.h"

namespace glint {

// Learning rates of one step, one per parameter (indexed by the table's index).
struct StepLearningRates {
  std::array<float, kGaussianParameterCount> rate{};

  // The rate of the parameter stored in `member`, e.g. of(&GaussianScene::position).
  template <typename V>
  float of(std::vector<V> GaussianScene::*member) const {
    return rate[parameterOf(member).index];
  }
};

// The rates at a step, as the parameter table names them: a decaying rate log-linear from
// its initial to its final value over its decay steps (constant at final afterwards; the
// position's times the scene extent), the others constant.
StepLearningRates learningRatesAt(const LearningRates& lr, float sceneExtent, int64_t step);

class AdamOptimizer {
 public:
  explicit AdamOptimizer(const AdamSettings& settings = {}) : settings_(settings) {}

  // Sizes the moments for n Gaussians (zeroed) and restarts the step count.
  void reset(size_t n);
  // One Adam step (step count t becomes t + 1) of every parameter of scene with its gradient.
  void step(GaussianScene* scene, const GaussianGradients& gradient, const StepLearningRates& rates);
  // Keeps the moments of the Gaussians whose keep[i] is true (after pruning).
  void filter(const std::vector<bool>& keep);
  // Appends zero moments for Gaussians added at the end of the scene (n >= the current size).
  void grow(size_t n);
  // Appends a copy of each listed Gaussian's moments (for the children of a split, which
  // continue their parent's optimisation), in the order of `from`.
  void appendCopies(std::span<const uint32_t> from);

  int64_t stepCount() const { return step_; }
  // The moments, for checkpoints (`weight` is unused).
  GaussianGradients& firstMoment() { return m_; }
  GaussianGradients& secondMoment() { return v_; }
  const GaussianGradients& firstMoment() const { return m_; }
  const GaussianGradients& secondMoment() const { return v_; }
  void setStepCount(int64_t step) { step_ = step; }

 private:
  AdamSettings settings_;
  GaussianGradients m_, v_;
  int64_t step_ = 0;
};

}  // namespace glint
