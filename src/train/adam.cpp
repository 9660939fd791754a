// Adam updates, parallel over Gaussians; each float of each array is one Adam parameter.
#include "train/adam.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace glint {

namespace {

// The float components of each parameter type, so that one Adam loop serves them all.
inline constexpr int componentCount(const float&) { return 1; }
inline constexpr int componentCount(const Vec3f&) { return 3; }
inline constexpr int componentCount(const Quatf&) { return 4; }
inline float& component(float& v, int) { return v; }
inline float component(const float& v, int) { return v; }
inline float& component(Vec3f& v, int k) { return v[k]; }
inline float component(const Vec3f& v, int k) { return v[k]; }
inline float& component(Quatf& q, int k) { return k == 0 ? q.w : k == 1 ? q.x : k == 2 ? q.y : q.z; }
inline float component(const Quatf& q, int k) { return k == 0 ? q.w : k == 1 ? q.x : k == 2 ? q.y : q.z; }

template <typename V>
void keepEntries(std::vector<V>* v, const std::vector<bool>& keep) {
  size_t out = 0;
  for (size_t i = 0; i < v->size(); ++i)
    if (keep[i]) (*v)[out++] = (*v)[i];
  v->resize(out);
}

}  // namespace

namespace {

// From init at step 0 to final at decaySteps (and after): log-linear, or linear when either
// end is zero.
double decayedRate(float init, float final, int decaySteps, int64_t step) {
  double t = std::clamp(double(step) / double(decaySteps), 0.0, 1.0);
  return init > 0 && final > 0 ? std::exp((1 - t) * std::log(double(init)) + t * std::log(double(final)))
                               : double(init) * (1 - t) + double(final) * t;
}

}  // namespace

StepLearningRates learningRatesAt(const LearningRates& lr, float extent, int64_t step) {
  double position = decayedRate(lr.positionInit, lr.positionFinal, lr.positionDecaySteps, step);
  double normal = decayedRate(lr.normal, lr.normalFinal, lr.normalDecaySteps, step);
  return {float(position * extent), lr.rotation, lr.scale,          lr.opacity,
          lr.diffuse,               float(normal), lr.roughness, lr.f0};
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
  auto group = [&](auto& param, const auto& grad, auto& m, auto& v, float lr, size_t begin, size_t end) {
    const float stepSize = float(lr / c1);
    for (size_t i = begin; i < end; ++i) {
      for (int k = 0; k < componentCount(param[i]); ++k) {
        float gk = component(grad[i], k);
        float& mk = component(m[i], k);
        float& vk = component(v[i], k);
        mk = b1 * mk + (1 - b1) * gk;
        vk = b2 * vk + (1 - b2) * gk * gk;
        component(param[i], k) -= stepSize * mk / (std::sqrt(vk) * invSqrtC2 + eps);
      }
    }
  };
  parallelForChunks(int64_t(n), 4096, [&](int64_t b, int64_t e) {
    size_t begin = size_t(b), end = size_t(e);
    group(scene->position, g.position, m_.position, v_.position, r.position, begin, end);
    group(scene->rotation, g.rotation, m_.rotation, v_.rotation, r.rotation, begin, end);
    group(scene->logScale, g.logScale, m_.logScale, v_.logScale, r.scale, begin, end);
    group(scene->opacityLogit, g.opacityLogit, m_.opacityLogit, v_.opacityLogit, r.opacity, begin, end);
    group(scene->diffuse, g.diffuse, m_.diffuse, v_.diffuse, r.diffuse, begin, end);
    group(scene->normal, g.normal, m_.normal, v_.normal, r.normal, begin, end);
    group(scene->roughness, g.roughness, m_.roughness, v_.roughness, r.roughness, begin, end);
    group(scene->f0, g.f0, m_.f0, v_.f0, r.f0, begin, end);
  });
}

void AdamOptimizer::filter(const std::vector<bool>& keep) {
  filterGradients(&m_, keep);
  filterGradients(&v_, keep);
}

void AdamOptimizer::grow(size_t n) {
  m_.grow(n);
  v_.grow(n);
}

void filterGradients(GaussianGradients* g, const std::vector<bool>& keep) {
  GLINT_CHECK(keep.size() == g->size(), "keep mask must match the gradient arrays");
  keepEntries(&g->position, keep);
  keepEntries(&g->rotation, keep);
  keepEntries(&g->logScale, keep);
  keepEntries(&g->opacityLogit, keep);
  keepEntries(&g->diffuse, keep);
  keepEntries(&g->normal, keep);
  keepEntries(&g->roughness, keep);
  keepEntries(&g->f0, keep);
  keepEntries(&g->weight, keep);
}

}  // namespace glint
