// Adam updates, parallel over Gaussians; each float of each parameter is one Adam parameter.
#include "train/adam.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace glint {

namespace {

// init until decayStart, then to final at decayStart + decaySteps (and after): log-linear,
// or linear when either end is zero.
double decayedRate(float init, float final, int decayStart, int decaySteps, int64_t step) {
  double t = std::clamp(double(step - decayStart) / double(decaySteps), 0.0, 1.0);
  return init > 0 && final > 0 ? std::exp((1 - t) * std::log(double(init)) + t * std::log(double(final)))
                               : double(init) * (1 - t) + double(final) * t;
}

}  // namespace

StepLearningRates learningRatesAt(const LearningRates& lr, float extent, int64_t step) {
  StepLearningRates rates;
  forEachParameter([&](const auto& p) {
    const ParameterRate& r = p.rate;
    if (!r.final) {
      rates.rate[p.index] = lr.*r.initial;
      return;
    }
    double rate = decayedRate(lr.*r.initial, lr.*r.final, lr.*r.decayStart, lr.*r.decaySteps, step);
    rates.rate[p.index] = float(r.timesSceneExtent ? rate * extent : rate);
  });
  return rates;
}

void AdamOptimizer::reset(size_t n) {
  m_.reset(n);
  v_.reset(n);
  step_ = 0;
}

void AdamOptimizer::step(GaussianScene* scene, const GaussianGradients& g, const StepLearningRates& r) {
  const size_t n = scene->size();
  GLINT_CHECK(g.size() == n && m_.size() == n, "Adam state and gradients must match the scene");
  ++step_;
  const float b1 = settings_.beta1, b2 = settings_.beta2, eps = settings_.epsilon;
  // Bias corrections folded into the step size and epsilon, as in PyTorch's Adam:
  // p -= lr / c1 * m / (sqrt(v) / sqrt(c2) + eps).
  const double c1 = 1.0 - std::pow(double(b1), double(step_));
  const double c2 = 1.0 - std::pow(double(b2), double(step_));
  const float invSqrtC2 = float(1.0 / std::sqrt(c2));
  parallelForChunks(int64_t(n), 4096, [&](int64_t begin, int64_t end) {
    forEachParameter([&](const auto& p) {
      constexpr int components = std::decay_t<decltype(p)>::components;
      auto* values = (scene->*p.values).data();
      const float* grad = g.values[p.index].data();
      float* m = m_.values[p.index].data();
      float* v = v_.values[p.index].data();
      const float stepSize = float(r.rate[p.index] / c1);
      for (int64_t i = begin; i < end; ++i) {
        for (int k = 0; k < components; ++k) {
          const size_t j = size_t(i) * components + k;
          m[j] = b1 * m[j] + (1 - b1) * grad[j];
          v[j] = b2 * v[j] + (1 - b2) * grad[j] * grad[j];
          component(values[i], k) -= stepSize * m[j] / (std::sqrt(v[j]) * invSqrtC2 + eps);
        }
      }
    });
  });
}

void AdamOptimizer::filter(const std::vector<bool>& keep) {
  m_.filter(keep);
  v_.filter(keep);
}

void AdamOptimizer::grow(size_t n) {
  m_.grow(n);
  v_.grow(n);
}

void AdamOptimizer::appendCopies(std::span<const uint32_t> from) {
  m_.appendCopies(from);
  v_.appendCopies(from);
}

}  // namespace glint
