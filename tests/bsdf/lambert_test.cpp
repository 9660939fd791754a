// Tests of the Lambertian lobe: chi-square of its sampling, weights, normalisation, albedo.
#include "bsdf/lambert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "common/chi_square.h"
#include "common/directions.h"
#include "math/rng.h"
#include "math/sampling.h"

namespace glint {
namespace {

using test::direction;
using test::kPiD;
using test::randomUpperDirection;


const LambertLobe kLobe{Rgb(0.8f, 0.5f, 0.2f)};
const Vec3f kLambertViews[] = {Vec3f(0, 0, 1), direction(0.05, 1.0)};

TEST(LambertChiSquare, SampleMatchesPdf) {
  const double significance = test::sidakSignificance(0.01, 2);
  uint64_t seed = 300;
  for (const Vec3f& wo : kLambertViews) {
    auto result = test::testDirectionSampler(
        test::DirectionGrid::hemisphere(),
        [&](Vec2f u) -> std::optional<Vec3f> {
          BsdfSample s = kLobe.sample(wo, u);
          return s.valid ? std::optional(s.wi) : std::nullopt;
        },
        [&](const Vec3f& wi) { return double(kLobe.pdf(wo, wi)); }, 200000, seed++, significance);
    EXPECT_TRUE(result.passed) << "wo.z = " << wo.z << ": " << result.message;
  }
}

TEST(Lambert, SampleWeightIsEvalOverPdf) {
  Rng rng(31);
  for (int k = 0; k < 10000; ++k) {
    Vec3f wo = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    BsdfSample s = kLobe.sample(wo, rng.uniform2());
    if (!s.valid) continue;
    ASSERT_GT(s.wi.z, 0.0f);
    float pdf = kLobe.pdf(wo, s.wi);
    Rgb ratio = kLobe.eval(wo, s.wi) / pdf;
    ASSERT_NEAR(s.pdf, pdf, 1e-6f * pdf);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], ratio[c], 1e-4f * ratio[c]);
    for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(s.weight[c], kLobe.albedo[c]);
  }
}

TEST(Lambert, PdfIntegratesToOneAndEvalToTheAlbedo) {
  for (const Vec3f& wo : kLambertViews) {
    auto grid = test::DirectionGrid::hemisphere();
    EXPECT_NEAR(grid.integrate([&](const Vec3f& wi) { return double(kLobe.pdf(wo, wi)); }, 1e-6), 1.0, 1e-4);
    // White furnace: a Lambertian surface reflects exactly its albedo.
    for (int c = 0; c < 3; ++c) {
      double reflected = grid.integrate([&](const Vec3f& wi) { return double(kLobe.eval(wo, wi)[c]); }, 1e-6);
      EXPECT_NEAR(reflected, kLobe.albedo[c], 1e-4);
    }
  }
}

TEST(Lambert, HelmholtzReciprocityAndReflectionOnly) {
  Rng rng(32);
  for (int k = 0; k < 1000; ++k) {
    Vec3f wo = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    Vec3f wi = direction(0.001 + 0.999 * rng.uniform(), 6.28 * rng.uniform());
    Rgb forward = kLobe.eval(wo, wi) / wi.z, backward = kLobe.eval(wi, wo) / wo.z;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(forward[c], backward[c], 1e-6f);
  }
  Vec3f up = direction(0.6, 0.2), down = direction(-0.6, 0.2);
  EXPECT_EQ(maxComponent(kLobe.eval(up, down)), 0.0f);
  EXPECT_EQ(maxComponent(kLobe.eval(down, up)), 0.0f);
  EXPECT_EQ(kLobe.pdf(up, down), 0.0f);
  EXPECT_FALSE(kLobe.sample(down, Vec2f(0.5f, 0.5f)).valid);
}

}  // namespace
}  // namespace glint
