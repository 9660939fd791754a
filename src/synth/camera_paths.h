// Camera placement for generated datasets: orbits around a target, and a default rig
// derived from a scene's bounds when the scene brings none.
#pragma once

#include <vector>

#include "math/mat4.h"
#include "synth/mesh_scene.h"

namespace glint {

// count camera-to-world matrices along the path. Full turns (turns >= 1) spread the views
// evenly without repeating the start; partial arcs include both ends.
std::vector<Mat4> orbitCameras(const OrbitPath& path, int count);

// A rig that looks at the bounds' centre from outside, far enough for the bounds to fit
// the field of view; train and test paths differ in radius, height and phase.
CameraRig defaultCameraRig(const Vec3f& lower, const Vec3f& upper, float fovX);

// The scene's own rig, or the default rig from its bounds when it brings none.
CameraRig sceneCameraRig(const MeshScene& scene);

}  // namespace glint
