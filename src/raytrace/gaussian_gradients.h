// Per-Gaussian gradient accumulators, one float array per parameter of the parameter table
// (scene/gaussian_parameters.h), plus the blend weight each Gaussian received (for weight
// pruning). Adam's moments are kept in the same form.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/cpu_gpu.h"
#include "math/quat.h"
#include "math/vec.h"
#include "scene/gaussian_parameters.h"

namespace glint {

// What the backward pass of one ray gives one of its hits (derivations D11-D12).
template <typename T>
struct HitGradient {
  Vec3<T> v_position;
  Quat<T> v_rotation{0, 0, 0, 0};
  Vec3<T> v_logScale;
  T v_opacityLogit = 0;
  Vec3<T> v_diffuse;
  Vec3<T> v_normal;
  T v_roughness = 0;
  Vec3<T> v_f0;
  T weight = 0;  // the hit's blend weight w_i = T_i alpha_i (not a gradient)
};

// The split score of one hit's gradient (densification, train/densify.h): how much the loss
// changes when the Gaussian moves by its own largest standard deviation `sigmaMax`, plus how
// much it changes per unit turn of its normal. Summing it over hits (not the gradient over hits first) keeps the pulls of
// rays that disagree, which cancel in the summed gradient: that disagreement is what a
// Gaussian too large for its detail shows.
GLINT_CPU_GPU inline float splitScore(const HitGradient<float>& g, float sigmaMax) {
  return length(g.v_position) * sigmaMax + length(g.v_normal);
}

struct GaussianGradients {
  // values[p.index] holds parameter p's components for every Gaussian, Gaussian i's at
  // [i * p.components, (i + 1) * p.components), in the order of component() (rotation's
  // is the adjoint of the stored, unnormalised quaternion).
  std::array<std::vector<float>, kGaussianParameterCount> values;
  std::vector<float> weight;  // accumulated blend weight

  size_t size() const { return weight.size(); }
  // Resizes to n Gaussians and zeroes everything.
  void reset(size_t n);
  // Resizes to n >= size() Gaussians, keeping the existing entries; new entries are zero.
  void grow(size_t n);
  // Zeroes the entries [begin, end) (so that parallel loops can clear their own ranges).
  void zero(size_t begin, size_t end);
  // Keeps the entries of the Gaussians whose keep[i] is true, in order.
  void filter(const std::vector<bool>& keep);
  // Appends a copy of each listed Gaussian's entries, in the order of `from`.
  void appendCopies(std::span<const uint32_t> from);

  // The floats of the parameter stored in `member`, e.g. of(&GaussianScene::roughness).
  template <typename V>
  std::span<float> of(std::vector<V> GaussianScene::*member) {
    return values[parameterOf(member).index];
  }
  template <typename V>
  std::span<const float> of(std::vector<V> GaussianScene::*member) const {
    return values[parameterOf(member).index];
  }

  // The backward pass names each output; each goes to its parameter's floats.
  template <typename T>
  void add(size_t i, const HitGradient<T>& g) {
    static_assert(kGaussianParameterCount == 8, "a new parameter's gradient is added here too");
    addTo<&GaussianScene::position>(i, g.v_position);
    addTo<&GaussianScene::rotation>(i, g.v_rotation);
    addTo<&GaussianScene::logScale>(i, g.v_logScale);
    addTo<&GaussianScene::opacityLogit>(i, g.v_opacityLogit);
    addTo<&GaussianScene::diffuse>(i, g.v_diffuse);
    addTo<&GaussianScene::normal>(i, g.v_normal);
    addTo<&GaussianScene::roughness>(i, g.v_roughness);
    addTo<&GaussianScene::f0>(i, g.v_f0);
    weight[i] += float(g.weight);
  }

  // Adds the entries [begin, end) of other into this (reduction of per-thread buffers).
  void addRange(const GaussianGradients& other, size_t begin, size_t end);

 private:
  template <auto member, typename V>
  void addTo(size_t i, const V& v) {
    constexpr auto parameter = parameterOf(member);
    // Every load before any store: as far as the compiler knows, out may alias v, and a
    // load after a store keeps it from adding the components with one vector instruction.
    float* out = values[parameter.index].data() + i * parameter.components;
    float sum[parameter.components];
    for (int k = 0; k < parameter.components; ++k) sum[k] = out[k] + float(component(v, k));
    for (int k = 0; k < parameter.components; ++k) out[k] = sum[k];
  }
};

}  // namespace glint
