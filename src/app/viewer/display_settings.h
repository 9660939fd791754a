// What the viewer shows and how: the buffer (render mode) or one reflected segment's light,
// path bounces, exposure and the denoise toggle, read from and written to the page's JSON.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "render/gaussian_path.h"
#include "scene/buffers.h"

namespace glint {

struct DisplaySettings {
  Buffer mode = Buffer::Render;  // "final" on the page is the render buffer
  // k > 0: only the light of reflected segment k ("bounce k" on the page), one term of the
  // specular buffer, so mode is then Buffer::Specular. 0: the whole buffer `mode`.
  int bounce = 0;
  int bounces = 2;               // reflected segments (0 = diffuse only)
  double exposure = 0;           // stops: radiance x 2^exposure before the tonemap
  bool denoise = false;

  static constexpr int kMaxBounces = 8;
  static constexpr double kMaxExposure = 10;
};
// Every bounce the viewer can trace can be shown alone.
static_assert(DisplaySettings::kMaxBounces <= kSeparateBounces);

// The page's name of the shown mode: "final", "diffuse", ..., "f0", or "bounce1", "bounce2", ...
std::string displayModeName(const DisplaySettings& settings);

nlohmann::json toJson(const DisplaySettings& settings);
// Applies the fields present in a request ({"mode", "bounces", "exposure", "denoise"}, all
// optional) to settings; throws RequestError for unknown fields or bad values, including a
// bounce mode beyond the bounce count the request leaves, leaving settings unchanged.
void applySettingsRequest(const nlohmann::json& request, DisplaySettings* settings);

// True when going from a to b changes the rendered samples (not only how they are shown):
// every bounce's light is accumulated, so switching between bounce modes re-shows them.
inline bool changesSamples(const DisplaySettings& a, const DisplaySettings& b) { return a.bounces != b.bounces; }

}  // namespace glint
