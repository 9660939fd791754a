// Camera paths: the ring recovered from known cameras, orbit and spiral geometry, and the
// dataset walk through its cameras.
#include "render/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

constexpr double kPiDouble = std::numbers::pi;

// Cameras on a circle of radius r at height h above target (up = +y), every one looking at
// the target, at heights h + bump_i.
std::vector<Mat4> circleCameras(Vec3d target, double r, double h, int count, double bump = 0) {
  std::vector<Mat4> cameras;
  for (int i = 0; i < count; ++i) {
    double a = 0.3 + 2 * kPiDouble * i / count;
    double hi = h + (i % 2 ? bump : -bump);
    cameras.push_back(Mat4::lookAt(target + Vec3d(r * std::cos(a), hi, r * std::sin(a)), target, {0, 1, 0}));
  }
  return cameras;
}

double distanceToAxis(const Mat4& camera, const Vec3d& p) {
  Vec3d o = camera.column(3), d = normalize(-camera.column(2));
  Vec3d v = p - o;
  return length(v - d * dot(v, d));
}

TEST(CameraPath, RingRecoversTheTargetRadiusAndHeight) {
  Vec3d target(1, 2, 3);
  CameraRing ring = cameraRing(circleCameras(target, 3.0, 1.0, 12, 0.25));
  EXPECT_NEAR(length(ring.target - target), 0.0, 1e-9);
  EXPECT_NEAR(length(ring.up - Vec3d(0, 1, 0)), 0.0, 1e-9);
  EXPECT_NEAR(ring.radius, 3.0, 1e-9);
  EXPECT_NEAR(ring.height, 1.0, 1e-9);
  EXPECT_NEAR(ring.lowest, 0.75, 1e-9);
  EXPECT_NEAR(ring.highest, 1.25, 1e-9);
  EXPECT_NEAR(dot(ring.startDirection, Vec3d(std::cos(0.3), 0, std::sin(0.3))), 1.0, 1e-9);
}

TEST(CameraPath, ParallelCamerasStillGiveAFiniteRing) {
  std::vector<Mat4> cameras = {Mat4::translation({0, 0, 5}), Mat4::translation({1, 0, 5})};  // both look down -z
  CameraRing ring = cameraRing(cameras);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isfinite(ring.target[i]));
  EXPECT_LT(ring.target.z, 5.0);  // ahead of the cameras
  std::vector<Mat4> path = makeCameraPath(CameraPathKind::Orbit, cameras, 8);
  for (const Mat4& m : path) EXPECT_TRUE(m.isAffine());
}

TEST(CameraPath, OrbitCirclesTheTargetAtTheRingsRadiusAndHeight) {
  Vec3d target(-0.5, 0.2, 0.7);
  std::vector<Mat4> cameras = circleCameras(target, 2.0, 0.8, 9);
  const int frames = 24;
  std::vector<Mat4> path = makeCameraPath(CameraPathKind::Orbit, cameras, frames);
  ASSERT_EQ(path.size(), size_t(frames));
  // The first frame stands where the first camera does.
  EXPECT_NEAR(length(path[0].column(3) - cameras[0].column(3)), 0.0, 1e-9);
  for (int f = 0; f < frames; ++f) {
    Vec3d offset = path[f].column(3) - target;
    EXPECT_NEAR(offset.y, 0.8, 1e-9);
    EXPECT_NEAR(std::hypot(offset.x, offset.z), 2.0, 1e-9);
    EXPECT_NEAR(distanceToAxis(path[f], target), 0.0, 1e-9);  // looks at the target
    EXPECT_GT(path[f].column(1).y, 0.0);                       // upright
    // Equal steps of one frame's share of a full turn.
    Vec3d next = path[(f + 1) % frames].column(3) - target;
    double step = std::atan2(offset.x * next.z - offset.z * next.x, offset.x * next.x + offset.z * next.z);
    EXPECT_NEAR(std::abs(step), 2 * kPiDouble / frames, 1e-9);
  }
}

TEST(CameraPath, SpiralRisesFromTheLowestCameraToTheHighestAndNarrows) {
  Vec3d target(0, 0, 0);
  std::vector<Mat4> cameras = circleCameras(target, 4.0, 1.0, 10, 0.5);  // heights 0.5 and 1.5
  const int frames = 40;
  std::vector<Mat4> path = makeCameraPath(CameraPathKind::Spiral, cameras, frames);
  double low = 1e9, high = -1e9;
  for (const Mat4& m : path) {
    Vec3d p = m.column(3);
    low = std::min(low, p.y), high = std::max(high, p.y);
    EXPECT_NEAR(distanceToAxis(m, target), 0.0, 1e-9);
  }
  EXPECT_NEAR(low, 0.5, 1e-9);
  EXPECT_NEAR(high, 1.5, 1e-9);
  Vec3d top = path[frames / 2].column(3);  // halfway: the top, at 80% of the radius
  EXPECT_NEAR(top.y, 1.5, 1e-9);
  EXPECT_NEAR(std::hypot(top.x, top.z), 0.8 * 4.0, 1e-9);
  // Two turns: halfway (one full turn) the azimuth is back at the start.
  Vec3d start = path[0].column(3), half = path[frames / 2].column(3);
  EXPECT_NEAR(std::atan2(start.z, start.x), std::atan2(half.z, half.x), 1e-9);
}

TEST(CameraPath, DatasetWalkKeepsTheCamerasAndInterpolatesSmoothlyBetweenThem) {
  std::vector<Mat4> cameras;
  for (int i = 0; i < 5; ++i) {
    double a = 0.4 * i;
    cameras.push_back(Mat4::lookAt({3 * std::cos(a), 1 + 0.1 * i, 3 * std::sin(a)}, {0, 0.2 * i, 0}, {0, 1, 0}));
  }
  std::vector<Mat4> same = makeCameraPath(CameraPathKind::DatasetTest, cameras, 5);
  for (int i = 0; i < 5; ++i)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(same[i].m[r][c], cameras[i].m[r][c]);

  // Twice as dense: every other frame is a dataset camera, and the ones between lie near
  // the chord between neighbours, looking in between.
  std::vector<Mat4> dense = makeCameraPath(CameraPathKind::DatasetTest, cameras, 9);
  ASSERT_EQ(dense.size(), 9u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(length(dense[2 * i].column(3) - cameras[i].column(3)), 0.0, 1e-9);
    EXPECT_NEAR(dot(normalize(-dense[2 * i].column(2)), normalize(-cameras[i].column(2))), 1.0, 1e-9);
  }
  for (int i = 0; i < 4; ++i) {
    Vec3d mid = dense[2 * i + 1].column(3);
    Vec3d a = cameras[i].column(3), b = cameras[i + 1].column(3);
    EXPECT_LT(length(mid - (a + b) * 0.5), 0.1 * length(b - a));
    Vec3d fa = normalize(-cameras[i].column(2)), fb = normalize(-cameras[i + 1].column(2));
    Vec3d fm = normalize(-dense[2 * i + 1].column(2));
    EXPECT_NEAR(dot(fm, normalize(fa + fb)), 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace glint
