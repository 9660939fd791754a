// Conversions of the viewer's camera.
#include "app/viewer/viewer_camera.h"

#include <cmath>

#include "app/viewer/request_json.h"

namespace glint {

Camera ViewerCamera::camera(int width, int height) const {
  Camera c = Camera::fromFieldOfView(Mat4::lookAt(eye, eye + forward, up), fovX, width, height);
  c.fy = c.fx * pixelAspect;
  c.cx = principalX * double(width);
  c.cy = principalY * double(height);
  return c;
}

ViewerCamera ViewerCamera::fromCameraToWorld(const Mat4& cameraToWorld, double fovX) {
  ViewerCamera c;
  c.eye = cameraToWorld.column(3);
  c.forward = normalize(-cameraToWorld.column(2));
  c.up = normalize(cameraToWorld.column(1));
  c.fovX = fovX;
  return c;
}

ViewerCamera ViewerCamera::fromCamera(const Camera& camera) {
  ViewerCamera c = fromCameraToWorld(camera.cameraToWorld, camera.fieldOfViewX());
  c.principalX = camera.cx / double(camera.width);
  c.principalY = camera.cy / double(camera.height);
  c.pixelAspect = camera.fy / camera.fx;
  return c;
}

nlohmann::json toJson(const ViewerCamera& c) {
  auto array = [](const Vec3d& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  nlohmann::json j = {{"eye", array(c.eye)}, {"forward", array(c.forward)}, {"up", array(c.up)}, {"fov_x", c.fovX}};
  if (c.principalX != 0.5 || c.principalY != 0.5) j["principal_point"] = {c.principalX, c.principalY};
  if (c.pixelAspect != 1.0) j["pixel_aspect"] = c.pixelAspect;
  return j;
}

ViewerCamera parseCameraRequest(const nlohmann::json& request) {
  requireOnlyFields(request, {"eye", "forward", "up", "fov_x", "principal_point", "pixel_aspect"});
  ViewerCamera c;
  c.eye = readVec3(request, "eye", ViewerCamera::kMaxCoordinate);
  c.forward = readVec3(request, "forward", ViewerCamera::kMaxCoordinate);
  c.up = readVec3(request, "up", ViewerCamera::kMaxCoordinate);
  c.fovX = readNumber(request, "fov_x", ViewerCamera::kMinFov, ViewerCamera::kMaxFov);
  if (request.contains("principal_point")) {
    const nlohmann::json& p = request["principal_point"];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw RequestError(400, "\"principal_point\" must be [x, y], fractions of the image");
    c.principalX = p[0].get<double>(), c.principalY = p[1].get<double>();
    if (!(c.principalX >= -1.0 && c.principalX <= 2.0 && c.principalY >= -1.0 && c.principalY <= 2.0))
      throw RequestError(400, "\"principal_point\" must lie in [-1, 2] (fractions of the image)");
  }
  if (request.contains("pixel_aspect")) c.pixelAspect = readNumber(request, "pixel_aspect", 0.1, 10.0);
  if (length(c.forward) < 1e-9) throw RequestError(400, "\"forward\" must not be zero");
  c.forward = normalize(c.forward);
  if (length(cross(c.forward, c.up)) < 1e-6 * length(c.up) || length(c.up) < 1e-9)
    throw RequestError(400, "\"up\" must not be zero or parallel to \"forward\"");
  c.up = normalize(c.up);
  return c;
}

}  // namespace glint
