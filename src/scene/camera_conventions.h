// The one place where camera conventions are converted: COLMAP's and nerfstudio's
// cameras to and from Glint's (docs/capture-format.md has the formulas).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/colmap_model.h"
#include "io/nerfstudio_transforms.h"
#include "io/point_cloud.h"
#include "math/mat4.h"
#include "math/vec.h"
#include "scene/camera.h"

namespace glint {

// A pinhole camera of a real capture in Glint's convention. cameraToWorld is rigid with
// OpenGL camera axes: x right, y up, the camera looks down -z. Pixel (i, j) (j counted
// from the top) has its centre at (i + 0.5, j + 0.5), and the ray through the continuous
// pixel position (px, py) has the camera-space direction ((px - cx)/fx, -(py - cy)/fy, -1).
// COLMAP and nerfstudio also put pixel centres at +0.5 and measure cx, cy from the
// image's top-left corner, so the intrinsics carry over unchanged.
struct CaptureCamera {
  std::string imageName;
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  Mat4 cameraToWorld = Mat4::identity();
};

// The unnormalised camera-space direction of the ray through pixel position (px, py).
Vec3d cameraRayDirection(const CaptureCamera& camera, double px, double py);

// A capture camera as Glint's Camera, and back (imageName is the only field a Camera lacks).
Camera toCamera(const CaptureCamera& camera);
CaptureCamera toCaptureCamera(const std::string& imageName, const Camera& camera);

// COLMAP stores world-to-camera (x_cam = R x_world + t) with OpenCV camera axes (x right,
// y down, z forward). cameraToWorld = [R^T diag(1, -1, -1) | -R^T t]; the world itself is
// COLMAP's, unchanged. The camera must project like a pinhole (colmapPinholeIntrinsics;
// throws Error otherwise); image.cameraId must be camera.id.
CaptureCamera fromColmap(const ColmapCamera& camera, const ColmapImage& image);

struct ColmapView {
  ColmapCamera camera;  // model PINHOLE: fx, fy, cx, cy
  ColmapImage image;    // qvec with w >= 0
};
// fromColmap inverted (up to the quaternion's sign, and SIMPLE_PINHOLE coming back as
// PINHOLE with fx = fy).
ColmapView toColmap(const CaptureCamera& camera, uint32_t cameraId, uint32_t imageId);

// nerfstudio's transform_matrix is already camera-to-world with OpenGL axes: it is used
// as it is, in the world of the transforms.json (see NerfstudioTransforms::appliedTransform).
CaptureCamera fromNerfstudio(const NerfstudioFrame& frame);
NerfstudioFrame toNerfstudio(const CaptureCamera& camera);

// COLMAP points as a coloured point cloud, mapped by colmapToWorld (the identity for
// cameras from fromColmap; a transforms.json's appliedTransform for its cameras).
PointCloud colmapPointCloud(const std::vector<ColmapPoint>& points, const Mat4& colmapToWorld = Mat4::identity());

struct CaptureScene {
  std::vector<CaptureCamera> cameras;  // sorted by image name
  PointCloud points;                   // in the cameras' world
};
// Every image of a model as a CaptureCamera, and its points (throws Error for a camera
// that is not a pinhole, or an image whose camera is missing).
CaptureScene captureFromColmap(const ColmapModel& model);
// Every frame of a transforms.json, sorted by file path.
std::vector<CaptureCamera> captureFromNerfstudio(const NerfstudioTransforms& transforms);

}  // namespace glint
