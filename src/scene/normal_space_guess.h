// Deciding from the data whether a predicted normal map is in camera or world space (and
// in which camera axes), so a loader can warn when the data contradicts what was declared.
#pragma once

#include <array>
#include <span>
#include <string>

#include "io/image.h"
#include "math/mat3.h"
#include "scene/predicted_buffers.h"

namespace glint {

enum class NormalSpace { World, Camera };

// One view of a normal map whose space is in doubt.
struct NormalSpaceView {
  const Image* normals = nullptr;  // 3 channels, unit or 0 ("no surface")
  Mat3d cameraToWorld;             // rotation, OpenGL camera axes
  RayIntrinsics intrinsics;
  const Image* zDepth = nullptr;  // optional, 1 channel: separates the x-mirrored axes
};

// The evidence and the verdict. A surface a pixel sees faces that pixel's camera, so under
// the right reading nearly every normal n satisfies n . (-ray) > 0; a wrong reading turns
// the normals by a rotation that depends on the view, and many fail the test.
struct NormalSpaceGuess {
  NormalSpace space = NormalSpace::World;
  CameraAxes axes = CameraAxes::OpenGl;  // the best camera-space reading
  // 0 when the readings cannot be told apart (e.g. a camera whose rotation is the identity
  // sees world and camera space alike), 1 when one reading fits and the other does not.
  double confidence = 0;
  // The same for the choice of camera axes. OpenGL and the paper's axes differ only by the
  // sign of x, which the facing test barely sees: without depth this stays near 0.
  double axesConfidence = 0;
  double worldFacing = 0;                               // fraction facing, read as world space
  std::array<double, kCameraAxesCount> cameraFacing{};  // read as camera space, per CameraAxes
  // Mean cosine between each camera-space reading and the normal of the depth map's surface
  // (-2 when no view gave depth).
  std::array<double, kCameraAxesCount> depthAgreement{-2, -2, -2};
  long pixels = 0;  // normals tested

  // "camera space (OpenGL axes), confidence 0.97: 99% face the camera read so, 52% read
  // as world space".
  std::string summary() const;
};

// Pools the pixels of all views: views with different rotations separate the readings
// better than one.
NormalSpaceGuess guessNormalSpace(std::span<const NormalSpaceView> views);
NormalSpaceGuess guessNormalSpace(const Image& normals, const Mat3d& cameraToWorld, const RayIntrinsics& k);

}  // namespace glint
