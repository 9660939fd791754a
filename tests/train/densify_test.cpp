// Densification by splitting: which Gaussians are chosen, and that the two children stand
// where their parent stood.
#include "train/densify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "math/quat.h"

namespace glint {
namespace {

TEST(Densify, ChoosesTheHighestScoresInIndexOrder) {
  const std::vector<float> score{0.5f, 3.0f, 0.0f, 2.0f, 3.0f, 1.0f, 0.1f, 2.0f};
  // ceil(0.3 x 8) = 3: the two 3.0s, then the first 2.0 (ties go to the lower index).
  EXPECT_EQ(chooseSplits(score, 0.3f, 100), (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_EQ(chooseSplits(score, 0.3f, 2), (std::vector<uint32_t>{1, 4})) << "room caps the count";
  EXPECT_TRUE(chooseSplits(score, 0.0f, 100).empty());
  // A zero score is never chosen, even when the fraction asks for everything.
  EXPECT_EQ(chooseSplits(score, 1.0f, 100).size(), 7u);
}

TEST(Densify, NeverChoosesANonFiniteOrZeroScore) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> score{nan, 0.0f, 1.0f, -2.0f};
  EXPECT_EQ(chooseSplits(score, 1.0f, 100), (std::vector<uint32_t>{2}));
}

GaussianScene oneGaussian() {
  GaussianScene s;
  s.resize(1);
  s.position[0] = Vec3f(1.0f, 2.0f, 3.0f);
  s.rotation[0] = quatFromAxisAngle(Vec3f(0.3f, -0.5f, 0.8f), 0.7f);
  s.logScale[0] = Vec3f(std::log(0.02f), std::log(0.3f), std::log(0.1f));  // longest: local y
  s.opacityLogit[0] = 0.4f;
  s.diffuse[0] = Rgb(0.2f, 0.5f, 0.7f);
  s.normal[0] = Vec3f(0.0f, 0.0f, 1.0f);
  s.roughness[0] = 0.3f;
  s.f0[0] = Rgb(0.9f, 0.6f, 0.3f);
  return s;
}

TEST(Densify, ChildrenStraddleTheParentAlongItsLongestAxis) {
  GaussianScene s = oneGaussian();
  const GaussianScene parent = s;
  const std::vector<uint32_t> which{0};
  splitGaussians(&s, which);
  ASSERT_EQ(s.size(), 2u);
  ASSERT_TRUE(s.consistent());
  const Mat3f r = quatToRotation(parent.rotation[0]);
  const Vec3f axis{r.m[0][1], r.m[1][1], r.m[2][1]};
  const Vec3f d0 = s.position[0] - parent.position[0], d1 = s.position[1] - parent.position[0];
  // +-0.5 sigma (0.15) along the longest axis, symmetric about the parent's mean.
  EXPECT_NEAR(dot(d0, axis), -0.15f, 1e-6f);
  EXPECT_NEAR(dot(d1, axis), 0.15f, 1e-6f);
  EXPECT_NEAR(length(d0 + d1), 0.0f, 1e-6f);
  EXPECT_NEAR(length(d1 - axis * dot(d1, axis)), 0.0f, 1e-6f);
  for (size_t c = 0; c < 2; ++c) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::exp(s.logScale[c][k]), std::exp(parent.logScale[0][k]) / 1.6f, 1e-6f);
    EXPECT_EQ(s.rotation[c].w, parent.rotation[0].w);
    EXPECT_EQ(s.opacityLogit[c], parent.opacityLogit[0]);
    EXPECT_EQ(s.diffuse[c], parent.diffuse[0]);
    EXPECT_EQ(s.normal[c], parent.normal[0]);
    EXPECT_EQ(s.roughness[c], parent.roughness[0]);
    EXPECT_EQ(s.f0[c], parent.f0[0]);
  }
}

TEST(Densify, SplitsAppendChildrenInTheOrderOfTheParents) {
  GaussianScene s = oneGaussian();
  s.append(oneGaussian(), 0);
  s.append(oneGaussian(), 0);
  s.position[1] = Vec3f(-5.0f, 0.0f, 0.0f);
  s.position[2] = Vec3f(7.0f, 0.0f, 0.0f);
  const std::vector<uint32_t> which{0, 2};
  splitGaussians(&s, which);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s.position[1], Vec3f(-5.0f, 0.0f, 0.0f)) << "an unsplit Gaussian stays as it was";
  EXPECT_NEAR(length(s.position[3] + s.position[0] - 2.0f * Vec3f(1.0f, 2.0f, 3.0f)), 0.0f, 1e-5f);
  EXPECT_NEAR(length(s.position[4] + s.position[2] - 2.0f * Vec3f(7.0f, 0.0f, 0.0f)), 0.0f, 1e-5f);
}

// The score is the loss change for a move by the Gaussian's own largest sigma plus that for
// a unit turn of the normal.
TEST(Densify, ScoreWeighsThePositionByTheSize) {
  HitGradient<float> g;
  g.v_position = Vec3f(3.0f, 0.0f, 4.0f);
  g.v_normal = Vec3f(0.0f, 0.6f, 0.8f);
  EXPECT_FLOAT_EQ(splitScore(g, 0.1f), 1.5f);
}

TEST(Densify, RejectsSettingsOutOfRange) {
  DensifySettings s;
  EXPECT_NO_THROW(checkDensifySettings(s, "config.json"));
  s.fraction = 1.5f;
  EXPECT_THROW(checkDensifySettings(s, "config.json"), Error);
  s = {};
  s.stop = s.start - 1;
  EXPECT_THROW(checkDensifySettings(s, "config.json"), Error);
  s = {};
  s.every = 0;
  EXPECT_THROW(checkDensifySettings(s, "config.json"), Error);
}

}  // namespace
}  // namespace glint
