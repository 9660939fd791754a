// Conversions of the viewer's camera.
#include "app/viewer/viewer_camera.h"

#include <cmath>

#include "app/viewer/request_json.h"

namespace glint {

Camera ViewerCamera::camera(int width, int height) const {
  return Camera::fromFieldOfView(Mat4::lookAt(eye, eye + forward, up), fovX, width, height);
}

ViewerCamera ViewerCamera::fromCameraToWorld(const Mat4& cameraToWorld, double fovX) {
  ViewerCamera c;
  c.eye = cameraToWorld.column(3);
  c.forward = normalize(-cameraToWorld.column(2));
  c.up = normalize(cameraToWorld.column(1));
  c.fovX = fovX;
  return c;
}

nlohmann::json toJson(const ViewerCamera& c) {
  auto array = [](const Vec3d& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"eye", array(c.eye)}, {"forward", array(c.forward)}, {"up", array(c.up)}, {"fov_x", c.fovX}};
}

ViewerCamera parseCameraRequest(const nlohmann::json& request) {
  requireOnlyFields(request, {"eye", "forward", "up", "fov_x"});
  ViewerCamera c;
  c.eye = readVec3(request, "eye", ViewerCamera::kMaxCoordinate);
  c.forward = readVec3(request, "forward", ViewerCamera::kMaxCoordinate);
  c.up = readVec3(request, "up", ViewerCamera::kMaxCoordinate);
  c.fovX = readNumber(request, "fov_x", ViewerCamera::kMinFov, ViewerCamera::kMaxFov);
  if (length(c.forward) < 1e-9) throw RequestError(400, "\"forward\" must not be zero");
  c.forward = normalize(c.forward);
  if (length(cross(c.forward, c.up)) < 1e-6 * length(c.up) || length(c.up) < 1e-9)
    throw RequestError(400, "\"up\" must not be zero or parallel to \"forward\"");
  c.up = normalize(c.up);
  return c;
}

}  // namespace glint
