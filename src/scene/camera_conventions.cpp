// Conversions between COLMAP's, nerfstudio's and Glint's camera conventions.
#include "scene/camera_conventions.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/error.h"
#include "io/colmap_camera_models.h"
#include "math/quat.h"

namespace glint {

namespace {

// The unit quaternion (w >= 0) of a rotation matrix, by Shepperd's method: the largest of
// 4w^2, 4x^2, 4y^2, 4z^2 (read off the diagonal) is taken as the divisor, which keeps the
// result accurate for every rotation.
Quatd rotationToQuaternion(const Mat3d& r) {
  const auto& m = r.m;
  double trace = m[0][0] + m[1][1] + m[2][2];
  Quatd q;
  if (trace > 0) {
    double s = 2 * std::sqrt(1 + trace);  // 4w
    q = {s / 4, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);  // 4x
    q = {(m[2][1] - m[1][2]) / s, s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] > m[2][2]) {
    double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);  // 4y
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s};
  } else {
    double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);  // 4z
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4};
  }
  q = q.normalized();
  if (q.w < 0) q = {-q.w, -q.x, -q.y, -q.z};  // q and -q are the same rotation
  return q;
}

}  // namespace

Vec3d cameraRayDirection(const CaptureCamera& camera, double px, double py) {
  return {(px - camera.cx) / camera.fx, -(py - camera.cy) / camera.fy, -1.0};
}

Camera toCamera(const CaptureCamera& c) {
  Camera camera;
  camera.cameraToWorld = c.cameraToWorld;
  camera.width = c.width, camera.height = c.height;
  camera.fx = c.fx, camera.fy = c.fy, camera.cx = c.cx, camera.cy = c.cy;
  return camera;
}

CaptureCamera toCaptureCamera(const std::string& imageName, const Camera& c) {
  CaptureCamera out;
  out.imageName = imageName;
  out.width = c.width, out.height = c.height;
  out.fx = c.fx, out.fy = c.fy, out.cx = c.cx, out.cy = c.cy;
  out.cameraToWorld = c.cameraToWorld;
  return out;
}

CaptureCamera fromColmap(const ColmapCamera& camera, const ColmapImage& image) {
  GLINT_CHECK(image.cameraId == camera.id, "fromColmap needs the image's own camera");
  PinholeIntrinsics k = colmapPinholeIntrinsics(camera, "COLMAP model", "");
  CaptureCamera out;
  out.imageName = image.name;
  out.width = camera.width;
  out.height = camera.height;
  out.fx = k.fx, out.fy = k.fy, out.cx = k.cx, out.cy = k.cy;
  // R maps world to OpenCV camera axes; its rows are the camera's axes in the world. The
  // OpenGL axes are (x, -y, -z) of OpenCV's, and the centre is -R^T t.
  Mat3d r = quatToRotation(image.qvec);
  Vec3d centre = -r.transposeTimes(image.tvec);
  const double flip[3] = {1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    for (int axis = 0; axis < 3; ++axis) out.cameraToWorld.m[i][axis] = flip[axis] * r.m[axis][i];
    out.cameraToWorld.m[i][3] = centre[i];
  }
  return out;
}

ColmapView toColmap(const CaptureCamera& camera, uint32_t cameraId, uint32_t imageId) {
  ColmapView view;
  view.camera.id = cameraId;
  view.camera.model = "PINHOLE";
  view.camera.width = camera.width;
  view.camera.height = camera.height;
  view.camera.params = {camera.fx, camera.fy, camera.cx, camera.cy};

  // The inverse of fromColmap: row a of R is flip[a] times column a of cameraToWorld.
  const Mat4& m = camera.cameraToWorld;
  const double flip[3] = {1, -1, -1};
  Mat3d r;
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i < 3; ++i) r.m[axis][i] = flip[axis] * m.m[i][axis];
  view.image.id = imageId;
  view.image.cameraId = cameraId;
  view.image.name = camera.imageName;
  view.image.qvec = rotationToQuaternion(r);
  view.image.tvec = -(r * m.column(3));
  return view;
}

CaptureCamera fromNerfstudio(const NerfstudioFrame& frame) {
  CaptureCamera out;
  out.imageName = frame.filePath;
  out.width = frame.width;
  out.height = frame.height;
  out.fx = frame.fx, out.fy = frame.fy, out.cx = frame.cx, out.cy = frame.cy;
  out.cameraToWorld = frame.transformMatrix;
  return out;
}

NerfstudioFrame toNerfstudio(const CaptureCamera& camera) {
  NerfstudioFrame frame;
  frame.filePath = camera.imageName;
  frame.width = camera.width;
  frame.height = camera.height;
  frame.fx = camera.fx, frame.fy = camera.fy, frame.cx = camera.cx, frame.cy = camera.cy;
  frame.transformMatrix = camera.cameraToWorld;
  return frame;
}

PointCloud colmapPointCloud(const std::vector<ColmapPoint>& points, const Mat4& colmapToWorld) {
  PointCloud cloud;
  cloud.positions.reserve(points.size());
  cloud.colors.reserve(points.size());
  for (const ColmapPoint& point : points) {
    cloud.positions.push_back(Vec3f(colmapToWorld.transformPoint(point.xyz)));
    cloud.colors.push_back(Rgb(point.rgb[0], point.rgb[1], point.rgb[2]) / 255.0f);
  }
  return cloud;
}

CaptureScene captureFromColmap(const ColmapModel& model) {
  std::unordered_map<uint32_t, const ColmapCamera*> cameras;
  for (const ColmapCamera& camera : model.cameras) cameras[camera.id] = &camera;
  CaptureScene scene;
  for (const ColmapImage& image : model.images) {
    auto camera = cameras.find(image.cameraId);
    if (camera == cameras.end())
      throw Error("COLMAP model", "image " + std::to_string(image.id) + " refers to camera " +
                                      std::to_string(image.cameraId) + ", which the model does not define");
    scene.cameras.push_back(fromColmap(*camera->second, image));
  }
  std::sort(scene.cameras.begin(), scene.cameras.end(),
            [](const CaptureCamera& a, const CaptureCamera& b) { return a.imageName < b.imageName; });
  scene.points = colmapPointCloud(model.points);
  return scene;
}

std::vector<CaptureCamera> captureFromNerfstudio(const NerfstudioTransforms& transforms) {
  std::vector<CaptureCamera> cameras;
  for (const NerfstudioFrame& frame : transforms.frames) cameras.push_back(fromNerfstudio(frame));
  std::sort(cameras.begin(), cameras.end(),
            [](const CaptureCamera& a, const CaptureCamera& b) { return a.imageName < b.imageName; });
  return cameras;
}

}  // namespace glint
