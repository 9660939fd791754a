// Tests of the GGX terms: closed forms, normalisation, the weak white furnace, and a
// chi-square test of visible-normal sampling.
#include "bsdf/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "common/chi_square.h"
#include "common/directions.h"
#include "common/ggx_reference.h"
#include "common/quadrature.h"
#include "math/rng.h"
#include "math/sampling.h"

namespace glint {
namespace {

using test::direction;
using test::kPiD;
using test::randomUpperDirection;




const float kMicrofacetAlphas[] = {0.05f, 0.2f, 0.5f, 1.0f};
// Normal, oblique, steep and grazing (87 degrees) views; azimuths avoid the grid's axes.
const Vec3f kMicrofacetViews[] = {Vec3f(0, 0, 1), direction(0.7, 0.4), direction(0.3, 2.0), direction(0.05, -2.5)};

TEST(Microfacet, DMatchesWaltersClosedForm) {
  // D = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2), Walter et al. 2007, evaluated in double
  // (tests/common/ggx_reference.h).
  for (float alpha : {kMinGgxAlpha, 0.05f, 0.3f, 1.0f}) {
    for (double cosTheta : {1.0, 0.9999, 0.95, 0.6, 0.2, 0.01}) {
      Vec3f wm = direction(cosTheta, 1.1);
      double expected = test::ggxDReference(Vec3d(wm), alpha);
      EXPECT_NEAR(D_GGX(wm, alpha), expected, 2e-5 * expected) << alpha << " " << cosTheta;
    }
  }
  EXPECT_EQ(D_GGX(Vec3f(0, 0.6f, -0.8f), 0.5f), 0.0f);  // no microfacets face downwards
}

TEST(Microfacet, LambdaMatchesClosedForm) {
  for (float alpha : {kMinGgxAlpha, 0.05f, 0.3f, 1.0f}) {
    for (double cosTheta : {1.0, 0.9, 0.5, 0.1, 0.001}) {
      Vec3f w = direction(cosTheta, -0.3);
      double expected = test::smithLambdaReference(Vec3d(w), alpha);
      EXPECT_NEAR(lambdaGGX(w, alpha), expected, 1e-5 * expected + 1e-12) << alpha << " " << cosTheta;
    }
  }
}

TEST(Microfacet, MaskingLimitsAndBounds) {
  Rng rng(11);
  for (float alpha : kMicrofacetAlphas) {
    EXPECT_FLOAT_EQ(smithG1(Vec3f(0, 0, 1), alpha), 1.0f);  // nothing is masked at normal view
    EXPECT_EQ(smithG1(Vec3f(1, 0, 0), alpha), 0.0f);        // everything is masked at the horizon
    EXPECT_EQ(smithG1(Vec3f(0, 0.6f, -0.8f), alpha), 0.0f);
    float previous = 1.0f;
    for (double cosTheta = 0.95; cosTheta > 0; cosTheta -= 0.05) {
      float g1 = smithG1(direction(cosTheta, 0.5), alpha);
      EXPECT_LE(g1, previous);  // masking grows towards grazing views
      previous = g1;
    }
    for (int k = 0; k < 100; ++k) {
      Vec3f wo = randomUpperDirection(rng);
      Vec3f wi = randomUpperDirection(rng);
      float g1o = smithG1(wo, alpha), g1i = smithG1(wi, alpha), g2 = smithG2(wo, wi, alpha);
      // Height correlation lies between independent (product) and fully correlated (min).
      EXPECT_GE(g2, g1o * g1i * (1 - 1e-6f));
      EXPECT_LE(g2, std::min(g1o, g1i) * (1 + 1e-6f));
      EXPECT_FLOAT_EQ(g2, smithG2(wi, wo, alpha));
    }
  }
}

TEST(Microfacet, DIsNormalised) {
  // Integral of D(wm) cos(theta_m) over the hemisphere is 1 (the microsurface projects onto
  // the unit macro area). D is isotropic: 2 pi Integral D(theta) cos sin dtheta, split at
  // geometric breakpoints so the adaptive rule sees peaks as narrow as alpha = 1e-3.
  for (float alpha : {kMinGgxAlpha, 0.01f, 0.05f, 0.2f, 0.5f, 1.0f}) {
    auto integrand = [&](double theta) {
      return D_GGX(direction(std::cos(theta), 0.0), alpha) * std::cos(theta) * std::sin(theta);
    };
    double integral = 0, start = 0;
    for (double end : {1e-5, 1e-4, 1e-3, 1e-2, 1e-1, kPiD / 2}) {
      integral += test::integrate1D(integrand, start, end, 1e-9);
      start = end;
    }
    EXPECT_NEAR(2 * kPiD * integral, 1.0, 1e-3) << "alpha = " << alpha;
  }
}

TEST(Microfacet, WeakWhiteFurnace) {
  // Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs":
  // with G1 in place of G2 and F = 1, the microfacet BRDF times cos(theta_i) integrates to
  // exactly 1 over the whole sphere of wi (reflections below the horizon included), for
  // any wo. Integrand: D(wm) G1(wo) / (4 wo.z) with wm = normalize(wo + wi).
  for (float alpha : kMicrofacetAlphas) {
    for (const Vec3f& wo : kMicrofacetViews) {
      auto integrand = [&](const Vec3f& wi) {
        Vec3f wm = normalize(wo + wi);
        return double(D_GGX(wm, alpha)) * smithG1(wo, alpha) / (4.0 * wo.z);
      };
      Vec3f mirror(-wo.x, -wo.y, wo.z);
      test::DirectionGrid grid = test::DirectionGrid::around(mirror, alpha < 0.1f ? 16 * alpha : kPiD);
      double integral = grid.integrate(integrand, 1e-4);
      EXPECT_NEAR(integral, 1.0, 1e-2) << "alpha = " << alpha << ", wo.z = " << wo.z;
    }
  }
}

// Narrow lobes get a window a few alpha wide around the normal, so that quadrature and
// histograms resolve them; the cell outside the window collects the tail.
test::DirectionGrid normalGrid(float alpha) {
  return test::DirectionGrid::around(Vec3f(0, 0, 1), alpha < 0.1f ? 8 * alpha : kPiD);
}

TEST(Microfacet, VisibleNormalPdfIntegratesToOne) {
  for (float alpha : kMicrofacetAlphas) {
    for (const Vec3f& wo : kMicrofacetViews) {
      auto pdf = [&](const Vec3f& wm) { return double(visibleNormalPdfGGX(wo, wm, alpha)); };
      double integral = normalGrid(alpha).integrate(pdf, 1e-4);
      EXPECT_NEAR(integral, 1.0, 1e-3) << "alpha = " << alpha << ", wo.z = " << wo.z;
    }
  }
}

TEST(Microfacet, NoVisibleNormalsBelowTheHorizon) {
  EXPECT_FALSE(sampleVisibleNormalGGX(Vec3f(0.6f, 0, -0.8f), 0.3f, Vec2f(0.3f, 0.6f)).has_value());
  EXPECT_FALSE(sampleVisibleNormalGGX(Vec3f(1, 0, 0), 0.3f, Vec2f(0.3f, 0.6f)).has_value());
  EXPECT_EQ(visibleNormalPdfGGX(Vec3f(0.6f, 0, -0.8f), Vec3f(0, 0, 1), 0.3f), 0.0f);
  // Corners of the unit square still give valid normals (or none), never NaN.
  for (Vec2f u : {Vec2f(0, 0), Vec2f(0, 0x1.fffffep-1f), Vec2f(0x1.fffffep-1f, 0), Vec2f(0.5f, 0x1.fffffep-1f)}) {
    for (const Vec3f& wo : kMicrofacetViews) {
      std::optional<Vec3f> wm = sampleVisibleNormalGGX(wo, kMinGgxAlpha, u);
      if (wm) {
        EXPECT_TRUE(isFinite(*wm));
        EXPECT_GT(wm->z, 0.0f);
      }
    }
  }
}

TEST(MicrofacetChiSquare, VisibleNormalSampling) {
  const double significance = test::sidakSignificance(0.01, 16);
  uint64_t seed = 100;
  for (float alpha : kMicrofacetAlphas) {
    for (const Vec3f& wo : kMicrofacetViews) {
      auto result = test::testDirectionSampler(
          normalGrid(alpha), [&](Vec2f u) { return sampleVisibleNormalGGX(wo, alpha, u); },
          [&](const Vec3f& wm) { return double(visibleNormalPdfGGX(wo, wm, alpha)); }, 500000, seed++, significance);
      EXPECT_TRUE(result.passed) << "alpha = " << alpha << ", wo.z = " << wo.z << ": " << result.message;
    }
  }
}

TEST(Microfacet, LobeLogAlphaDerivativeMatchesFiniteDifferences) {
  Rng rng(31);
  for (double alpha : {0.002, 0.03, 0.2, 0.6, 1.0}) {
    for (int k = 0; k < 200; ++k) {
      Vec3d wo(randomUpperDirection(rng, 0.05f)), wi(randomUpperDirection(rng, 0.05f));
      if (k == 0) wi = Vec3d(-wo.x, -wo.y, wo.z);  // the mirror direction: wm = n
      double h = 1e-6 * alpha;
      double numeric = (std::log(test::ggxLobeReference(wo, wi, alpha + h)) -
                        std::log(test::ggxLobeReference(wo, wi, alpha - h))) /
                       (2 * h);
      double analytic = lobeLogAlphaDerivative(wo, wi, alpha);
      EXPECT_NEAR(analytic, numeric, 1e-6 * std::max(1.0, std::abs(numeric))) << alpha << " " << k;
      // The float version training runs agrees to float rounding.
      float single = lobeLogAlphaDerivative(Vec3f(wo), Vec3f(wi), float(alpha));
      EXPECT_NEAR(single, analytic, 1e-4 * std::max(1.0, std::abs(analytic))) << alpha << " " << k;
    }
  }
}

}  // namespace
}  // namespace glint
