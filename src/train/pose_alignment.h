// A view's camera pose aligned to the model being trained: the rigid change that makes the
// view's own colour target agree with the model's render from the current camera, by direct
// image alignment (robust Gauss-Newton over the six parameters of a rigid motion, the render's
// pixels carried into the target through the render's depth), coarse to fine.
#pragma once

#include <string>

#include "io/image.h"
#include "math/mat3.h"
#include "math/vec.h"
#include "scene/camera.h"

namespace glint {

struct PoseAlignmentOptions {
  int levels = 3;             // image pyramid levels, each half the size of the last (fewer on small images)
  int iterations = 15;        // Levenberg-Marquardt iterations per level
  double huberDelta = 0.04;   // residuals beyond this (in c / (1 + c) display values) weigh less: occlusions, reflections
  double maxRotationDegrees = 3.0;  // larger changes are refused (a wrong basin, not a camera's error)
  double maxTranslation = 0.05;     // as a fraction of the render's median depth
  int minPixels = 200;        // render pixels with a surface needed at full resolution
  double minImprovement = 0.005;  // the robust cost must fall by this fraction to accept
};

struct PoseAlignment {
  bool accepted = false;
  Camera camera;              // the aligned camera (the given one when not accepted)
  double rotationDegrees = 0;  // the change's angle
  double translation = 0;      // the change's distance, in the scene's units
  double costBefore = 0, costAfter = 0;  // mean robust cost per residual at full resolution
  int pixels = 0;             // render pixels with a surface
  std::string refusal;        // why not accepted ("" when accepted)
  bool beyondBounds = false;  // refused as a turn or move beyond the options' bounds
};

// The camera pose at which `target` (a view's colour target, linear radiance, the size of
// `camera`) agrees best with `renderColour` and `renderDepth` (the model seen from `camera`
// through pixel centres; depth is the distance along the ray, no surface where 0 or
// >= kNoSurfaceDepth). The intrinsics stay. Refused (the given camera kept) when fewer than
// options.minPixels pixels have a surface, the cost does not fall, or the change exceeds the
// options' bounds.
PoseAlignment alignCameraPose(const Camera& camera, const Image& renderColour, const Image& renderDepth,
                              const Image& target, const PoseAlignmentOptions& options = {});

// The rigid change of camera coordinates Q = R P + t applied to a camera: its world-to-camera
// map becomes (R, t) after the old one, so a point at camera coordinates P before is at Q after.
Camera movedCamera(const Camera& camera, const Mat3d& r, const Vec3d& t);

// The rotation exp([w]x) of angle |w| about w (Rodrigues' formula).
Mat3d rotationFromVector(const Vec3d& w);

// The continuous pixel position (pixel centres at i + 0.5) that camera coordinates q project
// to under focal lengths fx, fy and principal point cx, cy (OpenGL axes, looking down -z), and
// its derivative by the left increment q' = q + w x q + v of the pose, columns (w, v):
// d(u, v)/d(w, v) = d(u, v)/dq [-[q]x | I]. False behind the camera.
bool projectWithPoseJacobian(const Vec3d& q, double fx, double fy, double cx, double cy, Vec2d* pixel,
                             double jacobian[2][6]);

}  // namespace glint
