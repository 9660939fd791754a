// The 18-byte training targets: each packing round-trips within its stated precision.
#include "train/packed_target.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "math/rng.h"

namespace glint {
namespace {

// Shared exponent: every channel within 2^-9 of the largest one (rounding to 9 bits; below
// 2^-16, the smallest exponent, within 2^-25), zero and negative values to 0, values beyond
// the range clamped.
TEST(PackedTarget, SharedExponentKeepsNineBitsOfTheLargestChannel) {
  Rng rng(7);
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.0f, rng.uniform() * 8.0f - 4.0f);  // 1e-4 .. 1e4
    Rgb c(rng.uniform() * scale, rng.uniform() * scale, rng.uniform() * scale);
    Rgb back = unpackSharedExponent(packSharedExponent(c));
    const float largest = std::max({c.x, c.y, c.z});
    const float bound = std::max(largest / 512.0f, kSmallestSharedExponentError);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(back[k] - c[k]), bound) << c.x << " " << c.y << " " << c.z;
  }
  EXPECT_EQ(unpackSharedExponent(packSharedExponent(Rgb(0.0f))), Rgb(0.0f));
  EXPECT_EQ(unpackSharedExponent(packSharedExponent(Rgb(-1.0f, 0.0f, -3.0f))), Rgb(0.0f));
  EXPECT_EQ(unpackSharedExponent(packSharedExponent(Rgb(1.0f, 2.0f, 4.0f))), Rgb(1.0f, 2.0f, 4.0f));  // exact
  EXPECT_FLOAT_EQ(unpackSharedExponent(packSharedExponent(Rgb(1e6f, 0.0f, 0.0f))).x, kMaxSharedExponentValue);
  EXPECT_EQ(unpackSharedExponent(packSharedExponent(Rgb(NAN, 0.5f, 0.5f))).x, 0.0f);
}

// Octahedral normals: under 0.05 degrees of error over the whole sphere (both halves).
TEST(PackedTarget, OctahedralNormalsRoundTripWithinAFewHundredthsOfADegree) {
  Rng rng(11);
  double worst = 0;
  for (int i = 0; i < 50000; ++i) {
    Vec3f n = normalize(Vec3f(rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1));
    Vec3f back = unpackOctahedral(packOctahedral(n));
    worst = std::max(worst, std::acos(std::min(1.0, double(dot(n, back)))) * 180.0 / std::numbers::pi);
  }
  EXPECT_LT(worst, 0.05);
  for (Vec3f axis : {Vec3f(1, 0, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1), Vec3f(0, 0, -1)})
    EXPECT_NEAR(length(unpackOctahedral(packOctahedral(axis)) - axis), 0.0, 1e-4);
}

// Depth as half: 11 significant bits; no surface (and depths beyond half's range) pack to 0.
TEST(PackedTarget, DepthKeepsElevenBitsAndMarksNoSurfaceByZero) {
  for (float d : {0.01f, 0.7f, 1.0f, 3.14159f, 27.5f, 900.0f, 60000.0f})
    EXPECT_LE(std::abs(unpackDepth(packDepth(d, true)) - d), d / 2048.0f) << d;
  EXPECT_EQ(packDepth(2.0f, false), 0);
  EXPECT_EQ(packDepth(1e9f, true), 0);
  EXPECT_NE(packDepth(0.0f, true), 0);  // a surface at the camera stays a surface
}

TEST(PackedTarget, Unorm8RoundsToTheNearestStep) {
  for (int i = 0; i <= 1000; ++i) {
    float v = float(i) / 1000.0f;
    EXPECT_LE(std::abs(unpackUnorm8(packUnorm8(v)) - v), 0.5f / 255.0f + 1e-7f);
  }
  EXPECT_EQ(packUnorm8(-0.5f), 0);
  EXPECT_EQ(packUnorm8(1.5f), 255);
}

}  // namespace
}  // namespace glint
