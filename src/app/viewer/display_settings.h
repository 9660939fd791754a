// What the viewer shows and how: the buffer (render mode), path bounces, exposure and the
// denoise toggle, read from and written to the page's JSON.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/buffers.h"

namespace glint {

struct DisplaySettings {
  Buffer mode = Buffer::Render;  // "final" on the page is the render buffer
  int bounces = 2;               // reflected segments (0 = diffuse only)
  double exposure = 0;           // stops: radiance x 2^exposure before the tonemap
  bool denoise = false;

  static constexpr int kMaxBounces = 8;
  static constexpr double kMaxExposure = 10;
};

// The page's name of a mode ("final", "diffuse", ..., "f0") and back.
const char* displayModeName(Buffer mode);
std::optional<Buffer> displayModeFromName(const std::string& name);

nlohmann::json toJson(const DisplaySettings& settings);
// Applies the fields present in a request ({"mode", "bounces", "exposure", "denoise"}, all
// optional) to settings; throws RequestError for unknown fields or bad values, leaving
// settings unchanged.
void applySettingsRequest(const nlohmann::json& request, DisplaySettings* settings);

// True when going from a to b changes the rendered samples (not only how they are shown).
inline bool changesSamples(const DisplaySettings& a, const DisplaySettings& b) { return a.bounces != b.bounces; }

}  // namespace glint
