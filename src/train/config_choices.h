// The training settings that choose between a few behaviours, as enums, and their one
// spelling each, shared by RUN/config.json and the flags of `glint train`.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/nerf_synthetic.h"
#include "train/camera_culling.h"

namespace glint {

// What is trained: the method, or the ray-traced RGB-only baseline (the first segment's
// colour fitted to the render buffer alone: no G-buffers, no reflections).
enum class Baseline { None, Rgb };

// Where the dense initialisation comes from: point_cloud_dense.ply when the dataset has
// one and the depth buffers otherwise (Auto), or the one named.
enum class InitChoice { Auto, DepthBuffers, PointCloud };

// The spellings of a choice enum: kNames lists every value once with its word.
template <typename E>
struct ChoiceNames;

template <>
struct ChoiceNames<Baseline> {
  static constexpr std::array<std::pair<Baseline, const char*>, 2> kNames{{{Baseline::None, "none"},
                                                                           {Baseline::Rgb, "rgb"}}};
};

template <>
struct ChoiceNames<InitChoice> {
  static constexpr std::array<std::pair<InitChoice, const char*>, 3> kNames{
      {{InitChoice::Auto, "auto"}, {InitChoice::DepthBuffers, "depth"}, {InitChoice::PointCloud, "point-cloud"}}};
};

template <>
struct ChoiceNames<CullRegion> {
  static constexpr std::array<std::pair<CullRegion, const char*>, 2> kNames{
      {{CullRegion::SphereInView, "in-view"}, {CullRegion::WholeSphere, "whole-sphere"}}};
};

template <>
struct ChoiceNames<AlphaBackground> {
  static constexpr std::array<std::pair<AlphaBackground, const char*>, 2> kNames{
      {{AlphaBackground::White, "white"}, {AlphaBackground::Black, "black"}}};
};

template <typename E>
concept Choice = requires { ChoiceNames<E>::kNames; };

template <Choice E>
const char* choiceName(E value) {
  for (const auto& [v, name] : ChoiceNames<E>::kNames)
    if (v == value) return name;
  return "?";  // unreachable: every value is listed
}

template <Choice E>
std::optional<E> choiceFromName(std::string_view name) {
  for (const auto& [v, spelling] : ChoiceNames<E>::kNames)
    if (name == spelling) return v;
  return std::nullopt;
}

// Every spelling, in order (for CLI::IsMember).
template <Choice E>
std::vector<std::string> choiceNames() {
  std::vector<std::string> names;
  for (const auto& entry : ChoiceNames<E>::kNames) names.emplace_back(entry.second);
  return names;
}

// "\"auto\", \"depth\" or \"point-cloud\"", for error messages.
template <Choice E>
std::string choiceList() {
  std::string text;
  const auto& names = ChoiceNames<E>::kNames;
  for (size_t i = 0; i < names.size(); ++i)
    text.append(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ").append("\"").append(names[i].second).append("\"");
  return text;
}

}  // namespace glint
