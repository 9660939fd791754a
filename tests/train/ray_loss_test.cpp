// The per-ray L1 losses: values on hand-made cases, the no-surface mask, and the VJP
// against central differences (away from the kinks of |x|).
#include "train/ray_loss.h"

#include <gtest/gtest.h>

#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

PixelTarget surfaceTarget() {
  PixelTarget t;
  t.diffuse = Rgb(0.5f, 0.25f, 0.125f);
  t.depth = 3.0f;
  t.normal = Vec3f(0.0f, 1.0f, 0.0f);
  t.roughness = 0.3f;
  t.f0 = Rgb(0.04f);
  t.surface = true;
  return t;
}

TEST(RayLoss, MeanAbsoluteErrorsPerTerm) {
  RayResult r;
  r.diffuse = Rgb(0.6f, 0.25f, 0.125f);
  r.depth = 2.0f;
  r.normal = Vec3f(0.0f, 0.5f, 0.0f);
  r.roughness = 0.5f;
  r.f0 = Rgb(0.04f, 0.04f, 0.34f);
  LossNormalisation n{4, 2};
  LossTerms t = rayLoss(r, surfaceTarget(), n);
  EXPECT_NEAR(t.diffuse, 0.1 / 3 / 4, 1e-7);
  EXPECT_NEAR(t.depth, 1.0 / 2, 1e-7);
  EXPECT_NEAR(t.normal, 0.5 / 3 / 2, 1e-7);
  EXPECT_NEAR(t.roughness, 0.2 / 2, 1e-7);
  EXPECT_NEAR(t.f0, 0.3 / 3 / 2, 1e-7);
  LossWeights w;
  EXPECT_NEAR(t.weighted(w), 5 * t.diffuse + 2.5 * t.depth + 10 * t.normal + t.roughness + t.f0, 1e-12);
}

TEST(RayLoss, NoSurfaceMasksTheGBufferTerms) {
  RayResult r;
  r.depth = 7.0f;
  r.normal = Vec3f(1.0f);
  PixelTarget t = surfaceTarget();
  t.surface = false;
  LossTerms terms = rayLoss(r, t, {1, 1});
  EXPECT_GT(terms.diffuse, 0);
  EXPECT_EQ(terms.depth, 0);
  EXPECT_EQ(terms.normal, 0);
  RayResultAdjoint v = rayLoss_vjp(r, t, {1, 1}, LossWeights());
  EXPECT_EQ(v.v_depth, 0);
  EXPECT_EQ(v.v_normal, Vec3f(0.0f));
  EXPECT_EQ(v.v_f0, Rgb(0.0f));
  EXPECT_NE(v.v_diffuse, Rgb(0.0f));
}

// The depth band (LossWeights::depthBand): a pixel counts when its depth is within the band's
// fraction of the prior's, and always without a band.
TEST(RayLoss, DepthBandKeepsThePixelsNearTheirPrior) {
  EXPECT_TRUE(withinDepthBand(3.2f, 3.0f, 0.1f));
  EXPECT_TRUE(withinDepthBand(2.8f, 3.0f, 0.1f));
  EXPECT_FALSE(withinDepthBand(3.4f, 3.0f, 0.1f));
  EXPECT_FALSE(withinDepthBand(2.6f, 3.0f, 0.1f));
  EXPECT_TRUE(withinDepthBand(30.0f, 3.0f, 0.0f));
}

// From a metalness prior the target is grey and only the brightest channels meet: a gold
// F0 against the grey 1 of a full metalness costs nothing, whatever its tint.
TEST(RayLoss, F0FromMetalnessComparesTheBrightestChannels) {
  PixelTarget t = surfaceTarget();
  t.f0 = Rgb(1.0f);
  t.f0BrightnessOnly = true;
  RayResult r;
  r.f0 = Rgb(1.0f, 0.78f, 0.34f);
  LossNormalisation n{4, 2};
  EXPECT_EQ(rayLoss(r, t, n).f0, 0.0);
  EXPECT_EQ(rayLoss_vjp(r, t, n, LossWeights()).v_f0, Rgb(0.0f));
  r.f0 = Rgb(0.5f, 0.8f, 0.2f);
  EXPECT_NEAR(rayLoss(r, t, n).f0, 0.2 / 2, 1e-7);
  const Rgb v = rayLoss_vjp(r, t, n, LossWeights()).v_f0;
  EXPECT_EQ(v.x, 0.0f);
  EXPECT_FLOAT_EQ(v.y, -1.0f / 2);  // only the brightest channel is pushed, up
  EXPECT_EQ(v.z, 0.0f);
  t.f0BrightnessOnly = false;  // the default compares every channel
  EXPECT_NEAR(rayLoss(r, t, n).f0, (0.5 + 0.2 + 0.8) / 3 / 2, 1e-7);
}

class RayLossVjp : public ::testing::TestWithParam<bool> {};

TEST_P(RayLossVjp, MatchesFiniteDifferences) {
  Rng rng(41);
  LossWeights w;
  LossNormalisation n{8, 5};
  PixelTarget target = surfaceTarget();
  target.f0BrightnessOnly = GetParam();
  if (GetParam()) target.f0 = Rgb(0.6f);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> x(11);
    for (double& v : x) v = rng.uniformDouble() * 4 - 1;
    auto unpack = [](const std::vector<double>& p) {
      RayResult r;
      r.diffuse = Rgb(float(p[0]), float(p[1]), float(p[2]));
      r.depth = float(p[3]);
      r.normal = Vec3f(float(p[4]), float(p[5]), float(p[6]));
      r.roughness = float(p[7]);
      r.f0 = Rgb(float(p[8]), float(p[9]), float(p[10]));
      return r;
    };
    // L1 is piecewise linear, so a difference quotient with a step that does not cross a
    // kink is exact; float inputs need a step far above their rounding.
    auto loss = [&](const std::vector<double>& p) { return rayLoss(unpack(p), target, n).weighted(w); };
    RayResultAdjoint v = rayLoss_vjp(unpack(x), target, n, w);
    std::vector<double> analytic = {v.v_diffuse.x, v.v_diffuse.y, v.v_diffuse.z, v.v_depth,   v.v_normal.x, v.v_normal.y,
                                    v.v_normal.z,  v.v_roughness, v.v_f0.x,      v.v_f0.y,     v.v_f0.z};
    test::expectGradientNear(analytic, test::centralGradient(loss, x, 1e-3), 1e-3, "ray loss");
  }
}

INSTANTIATE_TEST_SUITE_P(F0Channels, RayLossVjp, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "BrightestChannel" : "EveryChannel"; });

}  // namespace
}  // namespace glint
