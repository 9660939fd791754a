// Display settings of the viewer and their JSON form.
#include "app/viewer/display_settings.h"

#include "app/viewer/request_json.h"

namespace glint {

const char* displayModeName(Buffer mode) { return mode == Buffer::Render ? "final" : bufferName(mode); }

std::optional<Buffer> displayModeFromName(const std::string& name) {
  if (name == "final") return Buffer::Render;
  if (name == "render") return std::nullopt;  // the page says "final"; one name per mode
  return bufferFromName(name);
}

nlohmann::json toJson(const DisplaySettings& s) {
  return {{"mode", displayModeName(s.mode)}, {"bounces", s.bounces}, {"exposure", s.exposure}, {"denoise", s.denoise}};
}

void applySettingsRequest(const nlohmann::json& request, DisplaySettings* settings) {
  requireOnlyFields(request, {"mode", "bounces", "exposure", "denoise"});
  DisplaySettings next = *settings;
  if (request.contains("mode")) {
    std::optional<Buffer> mode = displayModeFromName(readString(request, "mode", 32));
    if (!mode) throw RequestError(400, "\"mode\" must be one of final, diffuse, specular, depth, normal, roughness, f0");
    next.mode = *mode;
  }
  if (request.contains("bounces")) next.bounces = readInteger(request, "bounces", 0, DisplaySettings::kMaxBounces);
  if (request.contains("exposure"))
    next.exposure = readNumber(request, "exposure", -DisplaySettings::kMaxExposure, DisplaySettings::kMaxExposure);
  if (request.contains("denoise")) next.denoise = readBool(request, "denoise");
  *settings = next;
}

}  // namespace glint
