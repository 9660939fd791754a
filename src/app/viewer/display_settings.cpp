// Display settings of the viewer and their JSON form.
#include "app/viewer/display_settings.h"

#include <optional>

#include "app/viewer/request_json.h"

namespace glint {

namespace {

constexpr const char* kBouncePrefix = "bounce";

// Sets mode and bounce from the page's name; throws RequestError 400 for an unknown one.
void setDisplayMode(const std::string& name, DisplaySettings* settings) {
  for (int k = 1; k <= DisplaySettings::kMaxBounces; ++k)
    if (name == kBouncePrefix + std::to_string(k)) {
      settings->mode = Buffer::Specular;
      settings->bounce = k;
      return;
    }
  std::optional<Buffer> buffer = name == "final" ? Buffer::Render : bufferFromName(name);
  // "render" is the file name of the final image; the page says "final", one name per mode.
  if (name.rfind(kBouncePrefix, 0) == 0 || !buffer || name == "render")
    throw RequestError(400, "\"mode\" must be one of final, diffuse, specular, depth, normal, roughness, f0, "
                            "bounce1 .. bounce" + std::to_string(DisplaySettings::kMaxBounces));
  settings->mode = *buffer;
  settings->bounce = 0;
}

}  // namespace

std::string displayModeName(const DisplaySettings& s) {
  if (s.bounce > 0) return kBouncePrefix + std::to_string(s.bounce);
  return s.mode == Buffer::Render ? "final" : bufferName(s.mode);
}

nlohmann::json toJson(const DisplaySettings& s) {
  return {{"mode", displayModeName(s)}, {"bounces", s.bounces}, {"exposure", s.exposure}, {"denoise", s.denoise}};
}

void applySettingsRequest(const nlohmann::json& request, DisplaySettings* settings) {
  requireOnlyFields(request, {"mode", "bounces", "exposure", "denoise"});
  DisplaySettings next = *settings;
  if (request.contains("mode")) setDisplayMode(readString(request, "mode", 32), &next);
  if (request.contains("bounces")) next.bounces = readInteger(request, "bounces", 0, DisplaySettings::kMaxBounces);
  if (request.contains("exposure"))
    next.exposure = readNumber(request, "exposure", -DisplaySettings::kMaxExposure, DisplaySettings::kMaxExposure);
  if (request.contains("denoise")) next.denoise = readBool(request, "denoise");
  // Checked on the result, so one request may lower the bounces and leave a bounce mode.
  if (next.bounce > next.bounces)
    throw RequestError(400, "mode \"" + displayModeName(next) + "\" needs at least " + std::to_string(next.bounce) +
                                " bounces (bounces is " + std::to_string(next.bounces) + ")");
  *settings = next;
}

}  // namespace glint
