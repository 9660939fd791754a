// Tests of Schlick's Fresnel approximation.
#include "bsdf/fresnel.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Fresnel, SchlickLimits) {
  for (Rgb F0 : {Rgb(0.04f), Rgb(0.9f, 0.6f, 0.3f), Rgb(0.0f), Rgb(1.0f)}) {
    Rgb normal = F_Schlick(F0, 1.0f), grazing = F_Schlick(F0, 0.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(normal[c], F0[c]);  // F(1) = F0
      EXPECT_FLOAT_EQ(grazing[c], 1.0f);  // F(0) = 1
    }
  }
}

TEST(Fresnel, SchlickIsMonotonicAndClamped) {
  Rgb F0(0.04f, 0.5f, 0.95f);
  Rgb previous = F_Schlick(F0, 1.0f);
  for (float cosTheta = 0.95f; cosTheta >= 0.0f; cosTheta -= 0.05f) {
    Rgb F = F_Schlick(F0, cosTheta);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(F[c], previous[c]);  // reflectance grows towards grazing angles
      EXPECT_LE(F[c], 1.0f);
    }
    previous = F;
  }
  // Cosines outside [0, 1] (from rounding) are clamped rather than extrapolated.
  EXPECT_FLOAT_EQ(F_Schlick(F0, 1.0001f)[0], 0.04f);
  EXPECT_FLOAT_EQ(F_Schlick(F0, -0.01f)[1], 1.0f);
  // Halfway: F0 + (1 - F0) / 32.
  EXPECT_NEAR(F_Schlick(F0, 0.5f)[1], 0.5f + 0.5f / 32, 1e-6f);
}

}  // namespace
}  // namespace glint
