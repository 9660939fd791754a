// Quaternion product and axis-angle construction agree with rotation matrices.
#include "math/quat.h"

#include <gtest/gtest.h>

#include <numbers>

namespace glint {
namespace {

void expectNear(const Mat3d& a, const Mat3d& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], 1e-12) << i << "," << j;
}

TEST(Quat, ProductComposesRotations) {
  Quatd a{0.3, -0.5, 0.7, 0.2}, b{-0.6, 0.1, 0.4, 0.9};
  expectNear(quatToRotation(a * b), quatToRotation(a) * quatToRotation(b));
}

TEST(Quat, AxisAngleRotatesRightHanded) {
  // 90 degrees about z takes x to y; about (1, 1, 1) by 120 degrees cycles the axes.
  Mat3d r = quatToRotation(quatFromAxisAngle(Vec3d(0, 0, 5), std::numbers::pi / 2));
  Vec3d y = r * Vec3d(1, 0, 0);
  EXPECT_NEAR(y.x, 0, 1e-15);
  EXPECT_NEAR(y.y, 1, 1e-15);
  Mat3d cycle = quatToRotation(quatFromAxisAngle(Vec3d(1, 1, 1), 2 * std::numbers::pi / 3));
  Vec3d z = cycle * Vec3d(0, 1, 0);
  EXPECT_NEAR(z.z, 1, 1e-12);
  EXPECT_NEAR(length(z), 1, 1e-12);
}

}  // namespace
}  // namespace glint
