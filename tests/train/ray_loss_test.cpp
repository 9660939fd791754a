// The per-ray losses: values on hand-made cases, the no-surface mask, the Huber normal term,
// and the VJPs against central differences (away from the kinks of |x|).
#include "train/ray_loss.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

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

// The tint prior (PixelTarget::f0TintPrior) blends the brightest channel's error with every
// channel's: kappa = 0 is the brightness alone, 1 the plain term, so a grey error scores the
// same whatever kappa, and a tint is pulled toward grey with a slope of kappa / 3.
TEST(RayLoss, F0TintPriorBlendsTheBrightnessWithEveryChannel) {
  PixelTarget t = surfaceTarget();
  t.f0 = Rgb(1.0f);
  t.f0BrightnessOnly = true;
  t.f0TintPrior = 0.25f;
  RayResult r;
  r.f0 = Rgb(0.5f, 0.8f, 0.2f);
  const LossNormalisation n{4, 2};
  EXPECT_NEAR(rayLoss(r, t, n).f0, (0.75 * 0.2 + 0.25 * (0.5 + 0.2 + 0.8) / 3) / 2, 1e-7);
  const Rgb v = rayLoss_vjp(r, t, n, LossWeights()).v_f0;
  EXPECT_FLOAT_EQ(v.x, -0.25f / 3 / 2);
  EXPECT_FLOAT_EQ(v.y, (-0.75f - 0.25f / 3) / 2);
  EXPECT_FLOAT_EQ(v.z, -0.25f / 3 / 2);
  r.f0 = Rgb(0.9f);  // grey: 0.1 off whatever kappa
  for (float kappa : {0.0f, 0.25f, 1.0f}) {
    t.f0TintPrior = kappa;
    EXPECT_NEAR(rayLoss(r, t, n).f0, 0.1 / 2, 1e-7) << kappa;
  }
  r.f0 = Rgb(1.0f, 0.78f, 0.34f);  // gold against a full metalness: costs only through kappa
  t.f0TintPrior = 1.0f;
  PixelTarget plain = t;
  plain.f0BrightnessOnly = false;
  EXPECT_NEAR(rayLoss(r, t, n).f0, rayLoss(r, plain, n).f0, 1e-7);
  EXPECT_EQ(rayLoss_vjp(r, t, n, LossWeights()).v_f0, rayLoss_vjp(r, plain, n, LossWeights()).v_f0);
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
    target.f0TintPrior = GetParam() && trial % 2 ? 0.3f : 0.0f;  // brightness alone, and blended
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

// The photograph term (LossWeights::photograph) is the mean absolute error of diffuse +
// specular against the photograph, weighted into the loss; its gradient with respect to
// that sum is the same for the diffuse and for the specular (checked by central
// differences in each, away from |x|'s kinks).
TEST(RayLoss, PhotographTermFitsDiffusePlusSpecular) {
  PixelTarget t = surfaceTarget();
  t.photograph = Rgb(0.9f, 0.5f, 0.2f);
  t.hasPhotograph = true;
  const LossNormalisation n{4, 2};
  const Rgb diffuse(0.5f, 0.25f, 0.125f), specular(0.3f, 0.35f, 0.025f);
  EXPECT_NEAR(photographLoss(diffuse + specular, t, n), (0.1 + 0.1 + 0.05) / 3 / 4, 1e-7);
  LossWeights w;
  w.photograph = 2.0f;
  EXPECT_EQ(photographLoss_vjp(diffuse + specular, t, n, w), Rgb(-2.0f, 2.0f, -2.0f) / 12.0f);
  LossTerms terms;
  terms.photograph = 0.5;
  EXPECT_NEAR(terms.weighted(w), 1.0, 1e-12);
  EXPECT_EQ(terms.weighted(LossWeights{}), 0.0);  // off by default
  Rng rng(43);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> x(6);  // diffuse, then specular
    for (double& v : x) v = rng.uniformDouble();
    auto sum = [](const std::vector<double>& p) {
      return Rgb(float(p[0] + p[3]), float(p[1] + p[4]), float(p[2] + p[5]));
    };
    auto loss = [&](const std::vector<double>& p) { return w.photograph * photographLoss(sum(p), t, n); };
    const Rgb v = photographLoss_vjp(sum(x), t, n, w);
    const std::vector<double> analytic = {v.x, v.y, v.z, v.x, v.y, v.z};
    test::expectGradientNear(analytic, test::centralGradient(loss, x, 1e-3), 1e-3, "photograph term");
  }
}

// The Huber normal term (LossWeights::normalHuber): quadratic within its width, L1's slope
// and offset beyond, continuous at the width; L1 itself with width 0.
TEST(RayLoss, HuberNormalPenaltyIsQuadraticWithinItsWidthAndL1Beyond) {
  EXPECT_DOUBLE_EQ(normalPenalty(-0.3f, 0.0f), double(0.3f));
  EXPECT_NEAR(normalPenalty(0.1f, 0.2f), 0.01 / 0.4, 1e-8);
  EXPECT_NEAR(normalPenalty(-0.5f, 0.2f), 0.5 - 0.1, 1e-7);
  EXPECT_NEAR(normalPenalty(0.2f, 0.2f), 0.1, 1e-7);
  EXPECT_EQ(normalPenalty_vjp(-0.3f, 0.0f), -1.0f);
  EXPECT_NEAR(normalPenalty_vjp(0.1f, 0.2f), 0.5f, 1e-6);
  EXPECT_EQ(normalPenalty_vjp(-0.5f, 0.2f), -1.0f);
  RayResult r;
  r.normal = Vec3f(0.1f, 0.9f, -0.5f);
  const LossNormalisation n{4, 2};
  const double huber = normalPenalty(0.1f, 0.2f) + normalPenalty(-0.1f, 0.2f) + normalPenalty(-0.5f, 0.2f);
  EXPECT_NEAR(rayLoss(r, surfaceTarget(), n, Rgb(0.0f), 0.2f).normal, huber / 3 / 2, 1e-7);
  EXPECT_NEAR(rayLoss(r, surfaceTarget(), n).normal, (0.1 + 0.1 + 0.5) / 3 / 2, 1e-7);
}

TEST(RayLoss, HuberNormalVjpMatchesFiniteDifferences) {
  Rng rng(43);
  LossWeights w;
  w.normalHuber = 0.4f;
  const LossNormalisation n{8, 5};
  const PixelTarget target = surfaceTarget();
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> x(3);
    for (double& v : x) v = rng.uniformDouble() * 2 - 0.5;  // around the target (0, 1, 0): both pieces
    auto unpack = [](const std::vector<double>& p) {
      RayResult r;
      r.normal = Vec3f(float(p[0]), float(p[1]), float(p[2]));
      return r;
    };
    auto loss = [&](const std::vector<double>& p) {
      return w.normal * rayLoss(unpack(p), target, n, Rgb(0.0f), w.normalHuber).normal;
    };
    const Vec3f v = rayLoss_vjp(unpack(x), target, n, w).v_normal;
    test::expectGradientNear({v.x, v.y, v.z}, test::centralGradient(loss, x, 1e-3), 1e-3, "Huber normal term");
  }
}

// What the option is for: the value minimising the summed penalty over many views' noisy
// priors of one normal component. Under L1 it is their median; with a Huber width of a few
// noise deviations, near their mean, whose spread is sqrt(2/pi) of the median's for Gaussian
// noise. Seeded: 4000 sets of 25 priors of deviation 0.05, width 0.2.
TEST(RayLoss, HuberNormalEstimateScattersLessThanL1sUnderGaussianNoise) {
  Rng rng(45);
  auto minimiser = [](const std::vector<float>& priors, float width) {
    double lo = -1, hi = 1;  // the summed penalty is convex: ternary search
    auto cost = [&](double x) {
      double c = 0;
      for (float p : priors) c += normalPenalty(float(x - p), width);
      return c;
    };
    for (int i = 0; i < 100; ++i) {
      const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      if (cost(a) < cost(b))
        hi = b;
      else
        lo = a;
    }
    return 0.5 * (lo + hi);
  };
  double l1Squares = 0, huberSquares = 0;
  const int sets = 4000;
  for (int s = 0; s < sets; ++s) {
    std::vector<float> priors(25);
    for (float& p : priors) {  // Box-Muller
      const double u = 1.0 - rng.uniformDouble(), v = rng.uniformDouble();
      p = float(0.05 * std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v));
    }
    l1Squares += std::pow(minimiser(priors, 0.0f), 2);
    huberSquares += std::pow(minimiser(priors, 0.2f), 2);
  }
  const double ratio = std::sqrt(huberSquares / l1Squares);
  // The median of 25 has an efficiency near 2/pi plus a small-sample correction: expect
  // about 0.81; the L1 estimate would give 1.
  EXPECT_GT(ratio, 0.74);
  EXPECT_LT(ratio, 0.88);
}

INSTANTIATE_TEST_SUITE_P(F0Channels, RayLossVjp, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "BrightestChannel" : "EveryChannel"; });

}  // namespace
}  // namespace glint
