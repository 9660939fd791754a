// Tests of the Cook-Torrance GGX lobe: sampling against its pdf (chi-square), weights,
// normalisation, reciprocity and the near-mirror limit.
#include "bsdf/cook_torrance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "bsdf/microfacet.h"
#include "common/chi_square.h"
#include "common/directions.h"
#include "math/rng.h"
#include "math/sampling.h"

namespace glint {
namespace {

using test::direction;
using test::kPiD;
using test::randomUpperDirection;




Vec3f mirror(const Vec3f& wo) { return Vec3f(-wo.x, -wo.y, wo.z); }

bool relativelyEqual(const Rgb& a, const Rgb& b, float tolerance) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(a[c] - b[c]) > tolerance * std::max(std::abs(a[c]), std::abs(b[c])) + 1e-30f) return false;
  return true;
}

const float kAlphas[] = {0.05f, 0.2f, 0.5f, 1.0f};
const Vec3f kViews[] = {Vec3f(0, 0, 1), direction(0.7, 0.4), direction(0.3, 2.0), direction(0.05, -2.5)};

// Reflected lobes are about twice as wide as the normal distribution; narrow ones get a
// window around the mirror direction so quadrature and histograms resolve them.
test::DirectionGrid reflectionGrid(const Vec3f& wo, float alpha) {
  return test::DirectionGrid::around(mirror(wo), alpha < 0.1f ? 16 * alpha : kPiD);
}

TEST(CookTorranceChiSquare, SampleMatchesPdf) {
  const double significance = test::sidakSignificance(0.01, 16);
  uint64_t seed = 200;
  for (float alpha : kAlphas) {
    for (const Vec3f& wo : kViews) {
      CookTorranceLobe lobe(Rgb(0.5f), alpha);
      auto result = test::testDirectionSampler(
          reflectionGrid(wo, alpha),
          [&](Vec2f u) -> std::optional<Vec3f> {
            BsdfSample s = lobe.sample(wo, u);
            return s.valid ? std::optional(s.wi) : std::nullopt;
          },
          [&](const Vec3f& wi) { return double(lobe.pdf(wo, wi)); }, 500000, seed++, significance);
      EXPECT_TRUE(result.passed) << "alpha = " << alpha << ", wo.z = " << wo.z << ": " << result.message;
    }
  }
}

TEST(CookTorrance, SampleWeightIsEvalOverPdf) {
  Rng rng(21);
  int valid = 0;
  for (int k = 0; k < 20000; ++k) {
    float alpha = kMinGgxAlpha + rng.uniform() * (1 - kMinGgxAlpha);
    CookTorranceLobe lobe(Rgb(rng.uniform(), rng.uniform(), rng.uniform()), alpha);
    Vec3f wo = randomUpperDirection(rng, 1e-3f);
    BsdfSample s = lobe.sample(wo, rng.uniform2());
    if (!s.valid) continue;
    ++valid;
    ASSERT_GT(s.wi.z, 0.0f);
    ASSERT_NEAR(length(s.wi), 1.0f, 1e-5f);
    float pdf = lobe.pdf(wo, s.wi);
    Rgb f = lobe.eval(wo, s.wi);
    ASSERT_NEAR(s.pdf, pdf, 1e-4f * pdf) << "alpha = " << alpha;
    ASSERT_TRUE(relativelyEqual(s.weight, f / pdf, 1e-4f))
        << "alpha = " << alpha << ": weight " << s.weight[0] << " vs eval / pdf " << (f / pdf)[0];
    // F <= 1 and G2 <= G1, so a single sample never gains energy.
    ASSERT_LE(maxComponent(s.weight), 1.0f + 1e-5f);
  }
  EXPECT_GT(valid, 15000);
}

TEST(CookTorrance, PdfIntegratesToTheFractionOfValidSamples) {
  // Samples reflected below the horizon are discarded, so the pdf over wi integrates to the
  // probability that a sample is valid. At normal incidence that is the probability of a
  // normal within 45 degrees of +z: the GGX slope distribution gives
  // P(tan^2 theta_m < t) = t / (alpha^2 + t), hence 1 / (1 + alpha^2).
  Rng rng(22);
  for (float alpha : kAlphas) {
    for (const Vec3f& wo : kViews) {
      CookTorranceLobe lobe(Rgb(1.0f), alpha);
      double integral =
          reflectionGrid(wo, alpha).integrate([&](const Vec3f& wi) { return double(lobe.pdf(wo, wi)); }, 1e-4);
      constexpr int kSamples = 100000;
      int valid = 0;
      for (int k = 0; k < kSamples; ++k) valid += lobe.sample(wo, rng.uniform2()).valid ? 1 : 0;
      EXPECT_NEAR(integral, double(valid) / kSamples, 1e-2) << "alpha = " << alpha << ", wo.z = " << wo.z;
      EXPECT_LE(integral, 1.0 + 1e-3);
      if (wo.z == 1.0f) {
        EXPECT_NEAR(integral, 1.0 / (1.0 + double(alpha) * alpha), 1e-3) << "alpha = " << alpha;
      }
    }
  }
}

TEST(CookTorrance, MeanSampleWeightIsTheDirectionalAlbedo) {
  // The sampling estimator is unbiased: the mean weight equals the integral of f cos.
  Rng rng(23);
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    for (const Vec3f& wo : {kViews[1], kViews[3]}) {
      CookTorranceLobe lobe(Rgb(1.0f, 0.5f, 0.04f), alpha);
      double albedo =
          reflectionGrid(wo, alpha).integrate([&](const Vec3f& wi) { return double(lobe.eval(wo, wi)[1]); }, 1e-4);
      constexpr int kSamples = 200000;
      double sum = 0;
      for (int k = 0; k < kSamples; ++k) {
        BsdfSample s = lobe.sample(wo, rng.uniform2());
        if (s.valid) sum += s.weight[1];
      }
      EXPECT_NEAR(sum / kSamples, albedo, 5e-3) << "alpha = " << alpha << ", wo.z = " << wo.z;
      EXPECT_LE(albedo, 1.0);
    }
  }
}

TEST(CookTorrance, HelmholtzReciprocity) {
  Rng rng(24);
  for (int k = 0; k < 10000; ++k) {
    CookTorranceLobe lobe(Rgb(rng.uniform(), rng.uniform(), rng.uniform()), 0.01f + rng.uniform());
    Vec3f wo = randomUpperDirection(rng, 1e-3f), wi = randomUpperDirection(rng, 1e-3f);
    // eval returns f cos(theta_i); f itself must be symmetric.
    Rgb forward = lobe.eval(wo, wi) / wi.z, backward = lobe.eval(wi, wo) / wo.z;
    ASSERT_TRUE(relativelyEqual(forward, backward, 1e-4f)) << forward[0] << " vs " << backward[0];
  }
}

TEST(CookTorrance, ReflectionOnly) {
  CookTorranceLobe lobe(Rgb(0.5f), 0.3f);
  Vec3f up = direction(0.6, 0.2), down(0.3f, 0.1f, -0.9487f);
  EXPECT_EQ(maxComponent(lobe.eval(up, down)), 0.0f);
  EXPECT_EQ(maxComponent(lobe.eval(down, up)), 0.0f);
  EXPECT_EQ(lobe.pdf(up, down), 0.0f);
  EXPECT_EQ(lobe.pdf(down, up), 0.0f);
  EXPECT_FALSE(lobe.sample(down, Vec2f(0.3f, 0.3f)).valid);
  EXPECT_FALSE(lobe.sample(Vec3f(1, 0, 0), Vec2f(0.3f, 0.3f)).valid);
}

TEST(CookTorrance, ZeroRoughnessIsANumericallySaneMirror) {
  CookTorranceLobe lobe(Rgb(0.9f), 0.0f);
  EXPECT_EQ(lobe.alpha, kMinGgxAlpha);
  Rng rng(25);
  for (double cosTheta : {1.0, 0.8, 0.3, 0.05}) {
    Vec3f wo = direction(cosTheta, 0.7);
    int far = 0;
    for (int k = 0; k < 1000; ++k) {
      BsdfSample s = lobe.sample(wo, rng.uniform2());
      if (!s.valid) continue;
      ASSERT_TRUE(isFinite(s.weight));
      ASSERT_TRUE(std::isfinite(s.pdf));
      // GGX has long tails, so only count samples more than 10 alpha off the mirror direction.
      if (dot(s.wi, mirror(wo)) < std::cos(10 * kMinGgxAlpha)) ++far;
      ASSERT_LE(maxComponent(s.weight), 1.0f + 1e-5f);
      ASSERT_TRUE(isFinite(lobe.eval(wo, s.wi)));
    }
    EXPECT_LT(far, 50) << "wo.z = " << wo.z;
    ASSERT_TRUE(isFinite(lobe.eval(wo, mirror(wo))));
    ASSERT_TRUE(std::isfinite(lobe.pdf(wo, mirror(wo))));
  }
}

// The detached-sampling gradient (docs/derivations.md D15): with a direction drawn by
// sample() and held fixed with its density, w d log f / d alpha is an unbiased estimate of
// d/d alpha of the integral of f cos L. Its mean over 2^20 samples agrees with central
// differences of that integral by quadrature, within four standard errors.
TEST(CookTorrance, DetachedAlphaGradientIsUnbiased) {
  Rng rng(29);
  for (float alpha : {0.1f, 0.3f, 0.7f}) {
    for (const Vec3f& wo : {kViews[1], kViews[2]}) {
      // Light peaked around the mirror direction, so the lobe's width changes what it reflects.
      auto radiance = [r = mirror(wo)](const Vec3f& wi) {
        return 0.2 + 2.0 * std::pow(std::max(0.0, double(dot(wi, r))), 8.0) + 0.3 * wi.x;
      };
      auto integral = [&](float a) {
        CookTorranceLobe lobe(Rgb(0.9f), a);
        return reflectionGrid(wo, alpha).integrate(
            [&](const Vec3f& wi) { return double(lobe.eval(wo, wi)[0]) * radiance(wi); }, 1e-7);
      };
      const float h = 0.02f * alpha;
      const double expected = (integral(alpha + h) - integral(alpha - h)) / (double(alpha + h) - double(alpha - h));
      CookTorranceLobe lobe(Rgb(0.9f), alpha);
      constexpr int kSamples = 1 << 20;
      double sum = 0, sumSquares = 0;
      for (int k = 0; k < kSamples; ++k) {
        BsdfSample s = lobe.sample(wo, rng.uniform2());
        if (!s.valid) continue;
        double x = double(s.weight[0]) * lobeLogAlphaDerivative(wo, s.wi, alpha) * radiance(s.wi);
        sum += x;
        sumSquares += x * x;
      }
      const double mean = sum / kSamples, error = std::sqrt((sumSquares / kSamples - mean * mean) / kSamples);
      EXPECT_NEAR(mean, expected, 4 * error + 1e-3 * std::abs(expected))
          << "alpha = " << alpha << ", wo.z = " << wo.z << ", standard error " << error;
      EXPECT_GT(std::abs(expected), 20 * error) << "the test should have teeth: " << expected << " " << error;
    }
  }
}

}  // namespace
}  // namespace glint
