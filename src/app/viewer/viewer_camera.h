// The viewer's camera as the page sends it: an eye point, a viewing direction, an up
// vector, a horizontal field of view and, for a dataset's camera, its principal point and
// pixel aspect; converted to a pinhole Camera at a given size.
#pragma once

#include <nlohmann/json.hpp>

#include "scene/camera.h"

namespace glint {

struct ViewerCamera {
  Vec3d eye{0.0, 0.0, 3.0};
  Vec3d forward{0.0, 0.0, -1.0};
  Vec3d up{0.0, 1.0, 0.0};
  double fovX = 0.8;  // radians
  // A capture's camera may have an off-centre principal point (a fraction of the image size)
  // and fy != fx; the page sends them back unchanged until the user moves the camera.
  double principalX = 0.5, principalY = 0.5;
  double pixelAspect = 1.0;  // fy / fx

  static constexpr double kMaxCoordinate = 1e6;  // scenes are metres across, not kilometres
  static constexpr double kMinFov = 0.01, kMaxFov = 3.0;

  Camera camera(int width, int height) const;
  static ViewerCamera fromCameraToWorld(const Mat4& cameraToWorld, double fovX);
  static ViewerCamera fromCamera(const Camera& camera);  // a dataset's view, intrinsics included
};

nlohmann::json toJson(const ViewerCamera& camera);
// Reads {"eye", "forward", "up", "fov_x"} (all required) and the optional
// "principal_point" [x, y] (fractions of the image, in [-1, 2]) and "pixel_aspect" (in
// [0.1, 10]); throws RequestError for a missing or non-finite value, a zero-length
// direction or up parallel to the direction.
ViewerCamera parseCameraRequest(const nlohmann::json& request);

}  // namespace glint
