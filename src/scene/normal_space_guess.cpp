// The facing test and the depth-agreement test behind guessNormalSpace.
#include "scene/normal_space_guess.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "scene/buffers.h"

namespace glint {

namespace {

constexpr CameraAxes kAllAxes[kCameraAxesCount] = {CameraAxes::OpenGl, CameraAxes::OpenCv, CameraAxes::PaperPrior};

// How decisively a winning fraction beats a losing one: a margin of 0.2 is decisive, and
// a winner near 0.5 (a coin toss) is no evidence at all.
double decisiveness(double winner, double loser) {
  double margin = std::clamp((winner - loser) / 0.2, 0.0, 1.0);
  double fit = std::clamp((winner - 0.5) / 0.4, 0.0, 1.0);
  return margin * fit;
}

struct Tally {
  long pixels = 0;
  long worldFacing = 0;
  std::array<long, kCameraAxesCount> cameraFacing{};
  long depthPixels = 0;
  std::array<double, kCameraAxesCount> depthCosineSum{};
};

// The camera-space point seen at the centre of pixel (i, j) at the depth map's z-depth.
Vec3d pointAt(const Image& zDepth, const RayIntrinsics& k, int i, int j) {
  return cameraRay(k, i + 0.5, j + 0.5) * double(zDepth.at(i, j));
}

// The normal of the depth map's surface at (i, j) from central differences, facing the
// camera (OpenGL axes); false at borders, holes and depth discontinuities.
bool depthNormal(const Image& zDepth, const RayIntrinsics& k, int i, int j, Vec3d* n) {
  if (i < 1 || j < 1 || i + 1 >= zDepth.width || j + 1 >= zDepth.height) return false;
  float z = zDepth.at(i, j);
  constexpr int kNeighbours[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  for (const auto& offset : kNeighbours) {
    float zn = zDepth.at(i + offset[0], j + offset[1]);
    if (!hasSurface(z) || !hasSurface(zn) || std::abs(zn - z) > 0.05f * z) return false;
  }
  Vec3d right = pointAt(zDepth, k, i + 1, j) - pointAt(zDepth, k, i - 1, j);
  Vec3d up = pointAt(zDepth, k, i, j - 1) - pointAt(zDepth, k, i, j + 1);  // rows grow downwards
  *n = normalize(cross(right, up));
  return length(*n) > 0;
}

void tallyView(const NormalSpaceView& view, Tally* tally) {
  const Image& normals = *view.normals;
  GLINT_CHECK(normals.channels == 3, "normal maps have three channels");
  bool withDepth = view.zDepth && view.zDepth->width == normals.width && view.zDepth->height == normals.height;
  for (int j = 0; j < normals.height; ++j)
    for (int i = 0; i < normals.width; ++i) {
      Vec3d n(normals.rgb(i, j));
      if (length(n) < kMinEncodedNormalLength) continue;
      Vec3d toCamera = -cameraRay(view.intrinsics, i + 0.5, j + 0.5);
      ++tally->pixels;
      tally->worldFacing += dot(view.cameraToWorld.transposeTimes(n), toCamera) > 0;
      for (int a = 0; a < kCameraAxesCount; ++a)
        tally->cameraFacing[a] += dot(toOpenGlAxes(n, kAllAxes[a]), toCamera) > 0;
      Vec3d surface;
      if (!withDepth || !depthNormal(*view.zDepth, view.intrinsics, i, j, &surface)) continue;
      ++tally->depthPixels;
      for (int a = 0; a < kCameraAxesCount; ++a)
        tally->depthCosineSum[a] += dot(normalize(toOpenGlAxes(n, kAllAxes[a])), surface);
    }
}

// The best and second-best entries of a score per axes.
std::pair<int, int> bestTwo(const std::array<double, kCameraAxesCount>& score) {
  int best = 0;
  for (int a = 1; a < kCameraAxesCount; ++a)
    if (score[a] > score[best]) best = a;
  int second = best == 0 ? 1 : 0;
  for (int a = 0; a < kCameraAxesCount; ++a)
    if (a != best && score[a] > score[second]) second = a;
  return {best, second};
}

}  // namespace

NormalSpaceGuess guessNormalSpace(std::span<const NormalSpaceView> views) {
  Tally tally;
  for (const NormalSpaceView& view : views) tallyView(view, &tally);

  NormalSpaceGuess guess;
  guess.pixels = tally.pixels;
  if (tally.pixels == 0) return guess;
  double total = double(tally.pixels);
  guess.worldFacing = tally.worldFacing / total;
  for (int a = 0; a < kCameraAxesCount; ++a) guess.cameraFacing[a] = tally.cameraFacing[a] / total;

  // Axes: by agreement with the depth map's surface when there is one, else by facing.
  auto [best, second] = bestTwo(guess.cameraFacing);
  guess.axesConfidence = decisiveness(guess.cameraFacing[best], guess.cameraFacing[second]);
  if (tally.depthPixels > 0) {
    for (int a = 0; a < kCameraAxesCount; ++a) guess.depthAgreement[a] = tally.depthCosineSum[a] / tally.depthPixels;
    std::tie(best, second) = bestTwo(guess.depthAgreement);
    // Cosines in [-1, 1] map to [0, 1] so that the same measure of decisiveness applies.
    guess.axesConfidence =
        decisiveness(0.5 + 0.5 * guess.depthAgreement[best], 0.5 + 0.5 * guess.depthAgreement[second]);
  }
  guess.axes = kAllAxes[best];

  double camera = guess.cameraFacing[best];
  guess.space = camera >= guess.worldFacing ? NormalSpace::Camera : NormalSpace::World;
  guess.confidence = guess.space == NormalSpace::Camera ? decisiveness(camera, guess.worldFacing)
                                                        : decisiveness(guess.worldFacing, camera);
  return guess;
}

NormalSpaceGuess guessNormalSpace(const Image& normals, const Mat3d& cameraToWorld, const RayIntrinsics& k) {
  NormalSpaceView view{&normals, cameraToWorld, k, nullptr};
  return guessNormalSpace(std::span<const NormalSpaceView>(&view, 1));
}

std::string NormalSpaceGuess::summary() const {
  char text[256];
  double camera = cameraFacing[int(axes)];
  if (space == NormalSpace::Camera)
    std::snprintf(text, sizeof text,
                  "camera space (%s axes), confidence %.2f: %.0f%% face the camera read so, %.0f%% read as world space",
                  cameraAxesName(axes), confidence, 100 * camera, 100 * worldFacing);
  else
    std::snprintf(text, sizeof text,
                  "world space, confidence %.2f: %.0f%% face the camera read so, %.0f%% read as camera space (%s axes)",
                  confidence, 100 * worldFacing, 100 * camera, cameraAxesName(axes));
  return text;
}

}  // namespace glint
