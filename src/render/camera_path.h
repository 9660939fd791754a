// Camera paths for videos (`glint render --path`): an orbit or a spiral around what a
// dataset's cameras look at, or a smooth walk through the test cameras in order.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "math/mat4.h"

namespace glint {

enum class CameraPathKind { Orbit, Spiral, DatasetTest };

// "orbit", "spiral", "dataset-test" and back.
const char* cameraPathName(CameraPathKind kind);
std::optional<CameraPathKind> cameraPathFromName(const std::string& name);

// Where a set of cameras stand and look, summarised for the orbit and the spiral.
struct CameraRing {
  Vec3d target;       // the point nearest to every optical axis (least squares)
  Vec3d up;           // the cameras' mean up vector, unit length
  Vec3d startDirection;  // unit, perpendicular to up: towards the first camera
  double radius = 1;  // mean distance of the cameras from the up axis through target
  double height = 0;  // mean height above target along up
  double lowest = 0, highest = 0;  // range of the heights
};

// Summarises camera-to-world matrices (OpenGL axes). Cameras whose axes are all parallel
// have no nearest point; the target is then the cameras' centroid moved one mean camera
// distance along the mean viewing direction. Needs at least one camera.
CameraRing cameraRing(const std::vector<Mat4>& cameras);

// frames camera-to-world matrices along the path:
// - Orbit: one full turn around ring.target at the mean radius and height, starting at the
//   first camera's azimuth, looking at the target.
// - Spiral: two turns whose height rises from the lowest to the highest camera and back
//   while the radius narrows to 80% at the top, looking at the target.
// - DatasetTest: the cameras themselves in order when frames equals their count, else a
//   Catmull-Rom curve through their positions with viewing and up directions blended
//   between neighbours, from the first camera to the last.
std::vector<Mat4> makeCameraPath(CameraPathKind kind, const std::vector<Mat4>& cameras, int frames);

}  // namespace glint
