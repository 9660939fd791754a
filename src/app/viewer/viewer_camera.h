// The viewer's camera as the page sends it: an eye point, a viewing direction, an up
// vector and a horizontal field of view; converted to a pinhole Camera at a given size.
#pragma once

#include <nlohmann/json.hpp>

#include "scene/camera.h"

namespace glint {

struct ViewerCamera {
  Vec3d eye{0.0, 0.0, 3.0};
  Vec3d forward{0.0, 0.0, -1.0};
  Vec3d up{0.0, 1.0, 0.0};
  double fovX = 0.8;  // radians

  static constexpr double kMaxCoordinate = 1e6;  // scenes are metres across, not kilometres
  static constexpr double kMinFov = 0.01, kMaxFov = 3.0;

  Camera camera(int width, int height) const;
  static ViewerCamera fromCameraToWorld(const Mat4& cameraToWorld, double fovX);
};

nlohmann::json toJson(const ViewerCamera& camera);
// Reads {"eye", "forward", "up", "fov_x"} (all required); throws RequestError for a missing
// or non-finite value, a zero-length direction or up parallel to the direction.
ViewerCamera parseCameraRequest(const nlohmann::json& request);

}  // namespace glint
