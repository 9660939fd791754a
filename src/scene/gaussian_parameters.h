// The trainable parameters of a Gaussian, listed once: resizing and filtering scenes,
// gradient buffers, Adam and its rates, checkpoints, PLY files and the divergence checks
// walk this table, so a new parameter is its array, one entry here and a default rate in
// LearningRates, plus its maths (docs/architecture.md, "The parameter table").
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "math/quat.h"
#include "math/vec.h"
#include "scene/gaussians.h"
#include "scene/learning_rates.h"

namespace glint {

// The float components of a parameter's value (float, Vec3 or Quat), in memory order, so
// that one loop serves every parameter. Checkpoints store the values as raw bytes and the
// moments as these floats, so the two orders must agree.
template <typename V>
inline constexpr int kComponents = sizeof(V) / sizeof(float);
static_assert(sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Quatf) == 4 * sizeof(float));

template <typename T>
  requires std::is_arithmetic_v<T>  // also a const float: T is then const
constexpr T& component(T& v, int) { return v; }
template <typename T>
constexpr T& component(Vec3<T>& v, int k) { return v[k]; }
template <typename T>
constexpr T component(const Vec3<T>& v, int k) { return v[k]; }
template <typename T>
constexpr T& component(Quat<T>& q, int k) { return k == 0 ? q.w : k == 1 ? q.x : k == 2 ? q.y : q.z; }
template <typename T>
constexpr T component(const Quat<T>& q, int k) { return k == 0 ? q.w : k == 1 ? q.x : k == 2 ? q.y : q.z; }

// How Adam's rate of a parameter is found in LearningRates, with the JSON keys (under
// "lr") of the members. A decaying rate stays at `initial` until step `decayStart`, then
// goes log-linearly to `final` over `decaySteps` steps (train/adam.h, learningRatesAt); the
// others stay at `initial`.
struct ParameterRate {
  float LearningRates::*initial = nullptr;
  const char* key = "";
  float LearningRates::*final = nullptr;  // null for a constant rate
  const char* finalKey = "";
  int LearningRates::*decaySteps = nullptr;
  const char* decayStepsKey = "";
  int LearningRates::*decayStart = nullptr;
  const char* decayStartKey = "";
  bool timesSceneExtent = false;  // position: the rate is in units of the scene's radius
};

// One parameter: an array of GaussianScene whose values are of type T.
template <typename T>
struct GaussianParameter {
  static constexpr int components = kComponents<T>;
  size_t index = 0;           // position in the table, the order of a checkpoint's arrays
  const char* name = "";      // the GaussianScene member
  const char* label = "";     // in messages ("a non-finite diffuse colour")
  std::vector<T> GaussianScene::*values = nullptr;
  T neutral{};                // of new Gaussians, and of an absent optional PLY group
  std::array<const char*, components> plyNames{};  // properties of Glint's PLY layout
  size_t plyOrder = 0;        // the group's place among the PLY columns (the paper's order)
  bool plyRequired = true;    // false: an optional group, all of its properties or none
  ParameterRate rate;
};

// Calls f(parameter) for every parameter, in table order.
template <typename F>
constexpr void forEachParameter(F&& f) {
  f(GaussianParameter<Vec3f>{.index = 0, .name = "position", .label = "position",
                             .values = &GaussianScene::position, .neutral = Vec3f(0.0f),
                             .plyNames = {"x", "y", "z"}, .plyOrder = 0,
                             .rate = {.initial = &LearningRates::positionInit, .key = "position_init",
                                      .final = &LearningRates::positionFinal, .finalKey = "position_final",
                                      .decaySteps = &LearningRates::positionDecaySteps,
                                      .decayStepsKey = "position_decay_steps",
                                      .decayStart = &LearningRates::positionDecayStart,
                                      .decayStartKey = "position_decay_start", .timesSceneExtent = true}});
  f(GaussianParameter<Quatf>{.index = 1, .name = "rotation", .label = "rotation",
                             .values = &GaussianScene::rotation, .neutral = Quatf{},
                             .plyNames = {"rot_0", "rot_1", "rot_2", "rot_3"}, .plyOrder = 4,
                             .rate = {.initial = &LearningRates::rotation, .key = "rotation"}});
  f(GaussianParameter<Vec3f>{.index = 2, .name = "logScale", .label = "scale",
                             .values = &GaussianScene::logScale, .neutral = Vec3f(0.0f),
                             .plyNames = {"scale_0", "scale_1", "scale_2"}, .plyOrder = 3,
                             .rate = {.initial = &LearningRates::scale, .key = "scale"}});
  f(GaussianParameter<float>{.index = 3, .name = "opacityLogit", .label = "opacity",
                             .values = &GaussianScene::opacityLogit, .neutral = 0.0f,
                             .plyNames = {"opacity"}, .plyOrder = 2,
                             .rate = {.initial = &LearningRates::opacity, .key = "opacity"}});
  f(GaussianParameter<Rgb>{.index = 4, .name = "diffuse", .label = "diffuse colour",
                           .values = &GaussianScene::diffuse, .neutral = Rgb(0.0f),
                           .plyNames = {"f_dc_0", "f_dc_1", "f_dc_2"}, .plyOrder = 1,
                           .rate = {.initial = &LearningRates::diffuse, .key = "diffuse"}});
  f(GaussianParameter<Vec3f>{.index = 5, .name = "normal", .label = "normal",
                             .values = &GaussianScene::normal, .neutral = Vec3f(0.0f),
                             .plyNames = {"normal_0", "normal_1", "normal_2"}, .plyOrder = 5,
                             .plyRequired = false,
                             .rate = {.initial = &LearningRates::normal, .key = "normal",
                                      .final = &LearningRates::normalFinal, .finalKey = "normal_final",
                                      .decaySteps = &LearningRates::normalDecaySteps,
                                      .decayStepsKey = "normal_decay_steps",
                                      .decayStart = &LearningRates::normalDecayStart,
                                      .decayStartKey = "normal_decay_start"}});
  f(GaussianParameter<float>{.index = 6, .name = "roughness", .label = "roughness",
                             .values = &GaussianScene::roughness, .neutral = 0.0f,
                             .plyNames = {"roughness"}, .plyOrder = 6, .plyRequired = false,
                             .rate = {.initial = &LearningRates::roughness, .key = "roughness",
                                      .final = &LearningRates::roughnessFinal, .finalKey = "roughness_final",
                                      .decaySteps = &LearningRates::roughnessDecaySteps,
                                      .decayStepsKey = "roughness_decay_steps",
                                      .decayStart = &LearningRates::roughnessDecayStart,
                                      .decayStartKey = "roughness_decay_start"}});
  f(GaussianParameter<Rgb>{.index = 7, .name = "f0", .label = "F0",
                           .values = &GaussianScene::f0, .neutral = Rgb(0.04f),
                           .plyNames = {"f0_0", "f0_1", "f0_2"}, .plyOrder = 7, .plyRequired = false,
                           .rate = {.initial = &LearningRates::f0, .key = "f0"}});
}

inline constexpr size_t kGaussianParameterCount = [] {
  size_t n = 0;
  forEachParameter([&](const auto&) { ++n; });
  return n;
}();

// The table's invariants, checked by the compiler: index counts entries in order, and
// plyOrder is a permutation of them (each PLY group written once).
inline constexpr bool kParameterTableWellFormed = [] {
  size_t next = 0, plyOrders = 0;
  bool ok = true;
  forEachParameter([&](const auto& p) {
    ok = ok && p.index == next++ && p.plyOrder < kGaussianParameterCount;
    plyOrders |= size_t(1) << p.plyOrder;
  });
  return ok && plyOrders == (size_t(1) << kGaussianParameterCount) - 1;
}();
static_assert(kParameterTableWellFormed, "parameter indices must count 0, 1, ... and plyOrder permute them");
// GaussianScene holds nothing but its parameter arrays, so an array without an entry shows.
static_assert(sizeof(GaussianScene) == kGaussianParameterCount * sizeof(std::vector<float>),
              "every array of GaussianScene needs an entry in forEachParameter");

// Calls f(parameter) for every parameter in the order of Glint's PLY columns.
template <typename F>
constexpr void forEachParameterInPlyOrder(F&& f) {
  for (size_t rank = 0; rank < kGaussianParameterCount; ++rank)
    forEachParameter([&](const auto& p) {
      if (p.plyOrder == rank) f(p);
    });
}

// The descriptor of the parameter stored in `values`, e.g. parameterOf(&GaussianScene::f0).
template <typename T>
constexpr GaussianParameter<T> parameterOf(std::vector<T> GaussianScene::*values) {
  GaussianParameter<T> found;
  forEachParameter([&](const auto& p) {
    if constexpr (std::is_same_v<std::decay_t<decltype(p)>, GaussianParameter<T>>)
      if (p.values == values) found = p;
  });
  return found;
}

// Keeps the entries of Gaussians whose keep[i] is true, in order: values holds `stride`
// entries per Gaussian (a parameter's floats in gradient and moment buffers).
template <typename V>
void keepSelected(std::vector<V>& values, const std::vector<bool>& keep, size_t stride = 1) {
  size_t out = 0;
  for (size_t i = 0; i < keep.size(); ++i)
    if (keep[i])
      for (size_t k = 0; k < stride; ++k) values[out++] = values[i * stride + k];
  values.resize(out);
}

}  // namespace glint
