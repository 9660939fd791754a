// Tests of the Lambert + Cook-Torrance mixture: chi-square of lobe-selection sampling,
// one-sample MIS weights, normalisation, unbiasedness, reciprocity and parameter mapping.
#include "bsdf/principled.h"

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


struct Case {
  const char* name;
  PrincipledBrdf brdf;
  Vec3f wo;
};

// A plastic seen from above and at a grazing angle (where Fresnel favours the specular
// lobe), a rough half-metal, and a pure metal (no diffuse lobe at all).
const Case kCases[] = {
    {"plastic", {Rgb(0.8f, 0.5f, 0.3f), Rgb(0.04f), 0.1f}, direction(0.8, 0.3)},
    {"grazing plastic", {Rgb(0.8f, 0.5f, 0.3f), Rgb(0.04f), 0.1f}, direction(0.1, 2.0)},
    {"rough half-metal", {Rgb(0.3f), Rgb(0.5f, 0.4f, 0.3f), 0.6f}, direction(0.5, -1.0)},
    {"metal", {Rgb(0.0f), Rgb(0.95f, 0.64f, 0.54f), 0.3f}, direction(0.6, 0.7)},
};

TEST(PrincipledChiSquare, MixtureSampleMatchesMixturePdf) {
  const double significance = test::sidakSignificance(0.01, 4);
  uint64_t seed = 400;
  for (const Case& c : kCases) {
    auto result = test::testDirectionSampler(
        test::DirectionGrid::hemisphere(16, 32),
        [&](Vec2f u) -> std::optional<Vec3f> {
          BsdfSample s = c.brdf.sample(c.wo, u);
          return s.valid ? std::optional(s.wi) : std::nullopt;
        },
        [&](const Vec3f& wi) { return double(c.brdf.pdf(c.wo, wi)); }, 500000, seed++, significance);
    EXPECT_TRUE(result.passed) << c.name << ": " << result.message;
  }
}

TEST(Principled, SampleWeightIsEvalOverPdf) {
  Rng rng(41);
  int valid = 0;
  for (int k = 0; k < 20000; ++k) {
    PrincipledBrdf brdf{Rgb(rng.uniform(), rng.uniform(), rng.uniform()),
                        Rgb(rng.uniform(), rng.uniform(), rng.uniform()),
                        PrincipledBrdf::alphaFromRoughness(rng.uniform())};
    Vec3f wo = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    BsdfSample s = brdf.sample(wo, rng.uniform2());
    if (!s.valid) continue;
    ++valid;
    ASSERT_GT(s.wi.z, 0.0f);
    float pdf = brdf.pdf(wo, s.wi);
    Rgb ratio = brdf.eval(wo, s.wi) / pdf;
    ASSERT_NEAR(s.pdf, pdf, 1e-4f * pdf);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], ratio[c], 1e-4f * ratio[c] + 1e-12f);
    ASSERT_TRUE(isFinite(s.weight));
  }
  EXPECT_GT(valid, 18000);
}

TEST(Principled, EvalAndPdfCombineTheLobes) {
  Rng rng(42);
  for (const Case& c : kCases) {
    float pSpecular = c.brdf.specularProbability(c.wo);
    for (int k = 0; k < 100; ++k) {
      Vec3f wi = direction(0.01 + 0.99 * rng.uniform(), 6.28 * rng.uniform());
      Rgb sum = c.brdf.diffuseLobe().eval(c.wo, wi) + c.brdf.specularLobe().eval(c.wo, wi);
      Rgb f = c.brdf.eval(c.wo, wi);
      for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(f[ch], sum[ch]);  // f = f_d + f_s, no (1 - F) coupling
      float mixture = pSpecular * c.brdf.specularLobe().pdf(c.wo, wi) +
                      (1 - pSpecular) * c.brdf.diffuseLobe().pdf(c.wo, wi);
      EXPECT_FLOAT_EQ(c.brdf.pdf(c.wo, wi), mixture);
    }
  }
}

TEST(Principled, PdfIntegratesToTheFractionOfValidSamples) {
  Rng rng(43);
  for (const Case& c : kCases) {
    double integral = test::DirectionGrid::hemisphere(16, 32).integrate(
        [&](const Vec3f& wi) { return double(c.brdf.pdf(c.wo, wi)); }, 1e-4);
    constexpr int kSamples = 100000;
    int valid = 0;
    for (int k = 0; k < kSamples; ++k) valid += c.brdf.sample(c.wo, rng.uniform2()).valid ? 1 : 0;
    EXPECT_NEAR(integral, double(valid) / kSamples, 1e-2) << c.name;
    EXPECT_LE(integral, 1.0 + 1e-3) << c.name;
  }
}

TEST(Principled, MeanSampleWeightIsTheDirectionalAlbedo) {
  // One-sample MIS is unbiased: the mean weight equals the integral of (f_d + f_s) cos.
  Rng rng(44);
  for (const Case& c : kCases) {
    for (int ch = 0; ch < 3; ch += 2) {
      double albedo = test::DirectionGrid::hemisphere(16, 32).integrate(
          [&](const Vec3f& wi) { return double(c.brdf.eval(c.wo, wi)[ch]); }, 1e-4);
      constexpr int kSamples = 200000;
      double sum = 0;
      for (int k = 0; k < kSamples; ++k) {
        BsdfSample s = c.brdf.sample(c.wo, rng.uniform2());
        if (s.valid) sum += s.weight[ch];
      }
      EXPECT_NEAR(sum / kSamples, albedo, 1e-2 * std::max(albedo, 0.1)) << c.name << ", channel " << ch;
    }
  }
}

TEST(Principled, HelmholtzReciprocity) {
  Rng rng(45);
  for (int k = 0; k < 10000; ++k) {
    PrincipledBrdf brdf{Rgb(rng.uniform()), Rgb(rng.uniform()), 0.01f + rng.uniform()};
    Vec3f wo = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    Vec3f wi = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    Rgb forward = brdf.eval(wo, wi) / wi.z, backward = brdf.eval(wi, wo) / wo.z;
    ASSERT_NEAR(forward[0], backward[0], 1e-4f * std::max(forward[0], backward[0]));
  }
}

TEST(Principled, AlphaFromRoughness) {
  EXPECT_FLOAT_EQ(PrincipledBrdf::alphaFromRoughness(0.0f), kMinGgxAlpha);
  EXPECT_FLOAT_EQ(PrincipledBrdf::alphaFromRoughness(-0.5f), kMinGgxAlpha);
  EXPECT_FLOAT_EQ(PrincipledBrdf::alphaFromRoughness(0.5f), 0.25f);
  EXPECT_FLOAT_EQ(PrincipledBrdf::alphaFromRoughness(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(PrincipledBrdf::alphaFromRoughness(2.0f), 1.0f);
}

TEST(Principled, LobeSelectionProbability) {
  const Vec3f normal(0, 0, 1), grazing = direction(0.05, 0.0);
  // A metal has no diffuse lobe to sample; a surface without any specular never samples it.
  EXPECT_EQ((PrincipledBrdf{Rgb(0.0f), Rgb(0.9f), 0.2f}.specularProbability(normal)), 1.0f);
  EXPECT_EQ((PrincipledBrdf{Rgb(0.5f), Rgb(0.0f), 0.2f}.specularProbability(normal)), 0.0f);
  // A plastic keeps both lobes alive, and favours specular more at grazing angles.
  PrincipledBrdf plastic{Rgb(0.8f), Rgb(0.04f), 0.2f};
  float pNormal = plastic.specularProbability(normal), pGrazing = plastic.specularProbability(grazing);
  EXPECT_GE(pNormal, PrincipledBrdf::kMinLobeProbability);
  EXPECT_LE(pGrazing, 1 - PrincipledBrdf::kMinLobeProbability);
  EXPECT_GT(pGrazing, pNormal);
}

TEST(Principled, ZeroRoughnessStaysFinite) {
  PrincipledBrdf brdf{Rgb(0.5f), Rgb(0.04f), PrincipledBrdf::alphaFromRoughness(0.0f)};
  Rng rng(46);
  for (int k = 0; k < 10000; ++k) {
    Vec3f wo = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    BsdfSample s = brdf.sample(wo, rng.uniform2());
    if (!s.valid) continue;
    ASSERT_TRUE(isFinite(s.weight));
    ASSERT_TRUE(std::isfinite(s.pdf));
    ASSERT_GT(s.pdf, 0.0f);
  }
  Vec3f wo = direction(0.7, 0.0);
  EXPECT_TRUE(isFinite(brdf.eval(wo, Vec3f(-wo.x, -wo.y, wo.z))));
}

TEST(Principled, ReflectionOnly) {
  const Case& c = kCases[0];
  Vec3f down = direction(-0.5, 0.3);
  EXPECT_EQ(maxComponent(c.brdf.eval(c.wo, down)), 0.0f);
  EXPECT_EQ(c.brdf.pdf(c.wo, down), 0.0f);
  EXPECT_FALSE(c.brdf.sample(down, Vec2f(0.3f, 0.6f)).valid);
  EXPECT_FALSE(c.brdf.sample(down, Vec2f(0.9f, 0.6f)).valid);
}

}  // namespace
}  // namespace glint
