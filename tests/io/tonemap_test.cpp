// The filmic tonemap: its closed-form inverse undoes it, and it is monotonic from 0.
#include "io/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

constexpr int kGridSteps = 640000;  // x in [0, 64] every 1e-4
constexpr float kGridMax = 64.0f;

float gridX(int i) { return kGridMax * float(i) / float(kGridSteps); }

TEST(Tonemap, ZeroMapsToZeroBothWays) {
  EXPECT_EQ(tonemapFilmic(0.0f), 0.0f);
  EXPECT_EQ(untonemapFilmic(0.0f), 0.0f);
  EXPECT_EQ(tonemapFilmic(-1.0f), 0.0f);  // negative radiance clamps to black
}

TEST(Tonemap, InverseUndoesTonemapOnDenseGrid) {
  // The published inverse rounds its constants to 4 digits, which leaves an absolute error
  // of about 1e-6 near 0: tolerance is 1e-4 relative, or absolute below 1.
  for (int i = 0; i <= kGridSteps; ++i) {
    float x = gridX(i);
    float back = untonemapFilmic(tonemapFilmic(x));
    ASSERT_NEAR(back, x, 1e-4f * std::max(1.0f, x)) << "x = " << x;
  }
}

TEST(Tonemap, MonotonicAndBelowOne) {
  float previous = tonemapFilmic(0.0f);
  for (int i = 1; i <= kGridSteps; ++i) {
    float y = tonemapFilmic(gridX(i));
    ASSERT_GE(y, previous) << "x = " << gridX(i);
    ASSERT_LT(y, 1.0f);
    previous = y;
  }
  // Strictly increasing where 8-bit images resolve it.
  EXPECT_LT(tonemapFilmic(0.1f), tonemapFilmic(0.2f));
  EXPECT_LT(tonemapFilmic(10.0f), tonemapFilmic(20.0f));
}

TEST(Tonemap, InverseSaturatesAtWhite) {
  EXPECT_EQ(untonemapFilmic(1.0f), kMaxUntonemapped);
  EXPECT_EQ(untonemapFilmic(2.0f), kMaxUntonemapped);
  EXPECT_GT(untonemapFilmic(254.5f / 255.0f), 64.0f);
}

TEST(Tonemap, RgbAppliesPerChannel) {
  Rgb c(0.0f, 0.5f, 3.0f);
  Rgb t = tonemapFilmic(c);
  EXPECT_EQ(t, Rgb(tonemapFilmic(0.0f), tonemapFilmic(0.5f), tonemapFilmic(3.0f)));
  Rgb back = untonemapFilmic(t);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], c[i], 1e-4f * std::max(1.0f, c[i]));
}

}  // namespace
}  // namespace glint
