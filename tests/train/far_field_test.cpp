// Far-field Gaussians: the truncated normal cloud has the paper's statistics, sizes from
// its own spacing, and the neutral attributes that end paths reaching it.
#include "train/far_field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace glint {
namespace {

// P(chi-square with k degrees of freedom <= x) for k = 3 and 5 in closed form.
double chiSquare3Cdf(double x) {
  double r = std::sqrt(x);
  return std::erf(r / std::sqrt(2.0)) - std::sqrt(2.0 / M_PI) * r * std::exp(-x / 2);
}
double chiSquare5Cdf(double x) { return chiSquare3Cdf(x) - std::sqrt(2.0 / M_PI) * std::pow(x, 1.5) * std::exp(-x / 2) / 3; }

TEST(FarField, CloudIsANormalDistributionTruncatedAtThreeSigma) {
  FarFieldSettings s;
  s.count = 40000;
  const Vec3f centre(1.0f, -2.0f, 0.5f);
  const float radius = 2.5f, sigma = s.sigmaFactor * radius;
  GaussianScene g = farFieldGaussians(s, centre, radius, 7);
  ASSERT_EQ(g.size(), size_t(s.count));
  ASSERT_TRUE(g.consistent());
  Vec3d mean(0.0), square(0.0);
  double outsideOneSigma = 0;
  for (const Vec3f& p : g.position) {
    Vec3d d = Vec3d(p - centre) / double(sigma);
    ASSERT_LE(length(d), s.truncation * (1 + 1e-5));
    mean += d;
    square += d * d;
    outsideOneSigma += length(d) > 1.0 ? 1 : 0;
  }
  const double n = double(g.size());
  mean /= n;
  square /= n;
  // Radial truncation at R sigma: E[x^2] per axis = P(chi2_5 <= R^2) / P(chi2_3 <= R^2).
  const double r2 = double(s.truncation) * s.truncation;
  const double axisVariance = chiSquare5Cdf(r2) / chiSquare3Cdf(r2);
  const double meanTolerance = 4.0 * std::sqrt(axisVariance / n);  // 4 standard errors
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean[a], 0.0, meanTolerance) << "axis " << a;
    // Var(x^2) <= E[x^4] = 3 for a unit normal: 4 standard errors of the mean of x^2.
    EXPECT_NEAR(square[a], axisVariance, 4.0 * std::sqrt(3.0 / n)) << "axis " << a;
  }
  // P(|x| > 1 sigma) for the truncated 3D normal.
  double expectedOutside = (chiSquare3Cdf(r2) - chiSquare3Cdf(1.0)) / chiSquare3Cdf(r2);
  EXPECT_NEAR(outsideOneSigma / n, expectedOutside, 4.0 * std::sqrt(0.25 / n));
}

TEST(FarField, AttributesEndPathsAndScalesFollowTheSpacing) {
  FarFieldSettings s;
  s.count = 300;
  s.opacity = 0.2f;
  s.diffuse = 0.3f;
  GaussianScene g = farFieldGaussians(s, Vec3f(0.0f), 1.0f, 1);
  for (size_t i = 0; i < g.size(); ++i) {
    EXPECT_EQ(g.normal[i], Vec3f(0.0f)) << "a zero normal ends paths that reach the far field";
    EXPECT_NEAR(g.opacity(i), 0.2f, 1e-6f);
    EXPECT_EQ(g.diffuse[i], Rgb(0.3f));
    EXPECT_EQ(g.rotation[i].w, 1.0f);
  }
  // Gaussian 0's scale is the mean distance to its 3 nearest neighbours (brute force).
  std::vector<float> d;
  for (size_t j = 1; j < g.size(); ++j) d.push_back(length(g.position[j] - g.position[0]));
  std::sort(d.begin(), d.end());
  float expected = (d[0] + d[1] + d[2]) / 3;
  EXPECT_NEAR(g.scale(0).x, expected, 1e-4f * expected);
  EXPECT_EQ(g.scale(0).x, g.scale(0).y);
}

// Boxes follow the cloud, uniformly filled: a chi-square test of 10 bins per axis.
TEST(FarField, BoxesAreFilledUniformly) {
  FarFieldSettings s;
  s.count = 100;
  const Vec3f lo(-1.0f, 0.0f, 2.0f), hi(1.0f, 0.5f, 3.0f);
  s.boxes.push_back({lo, hi, 20000});
  GaussianScene g = farFieldGaussians(s, Vec3f(0.0f), 1.0f, 5);
  ASSERT_EQ(g.size(), 20100u);
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> bins(10, 0.0);
    for (size_t i = 100; i < g.size(); ++i) {
      float u = (g.position[i][axis] - lo[axis]) / (hi[axis] - lo[axis]);
      ASSERT_TRUE(u >= 0.0f && u <= 1.0f) << "Gaussian " << i << " outside its box";
      bins[std::min(9, int(u * 10))] += 1;
    }
    double chi2 = 0;
    for (double b : bins) chi2 += (b - 2000) * (b - 2000) / 2000;
    EXPECT_LT(chi2, 27.88) << "axis " << axis;  // 9 degrees of freedom, p = 0.001
  }
  // Box Gaussians are sized by their own, denser spacing: (volume / count)^(1/3) = 0.037.
  EXPECT_LT(g.scale(100).x, 0.1f);
  EXPECT_EQ(g.normal[20099], Vec3f(0.0f));
}

TEST(FarField, DependsOnlyOnTheSeed) {
  FarFieldSettings s;
  s.count = 500;
  GaussianScene a = farFieldGaussians(s, Vec3f(0.0f), 1.0f, 3), b = farFieldGaussians(s, Vec3f(0.0f), 1.0f, 3);
  GaussianScene c = farFieldGaussians(s, Vec3f(0.0f), 1.0f, 4);
  EXPECT_EQ(a.position, b.position);
  EXPECT_NE(a.position, c.position);
  s.count = 0;
  EXPECT_TRUE(farFieldGaussians(s, Vec3f(0.0f), 1.0f, 3).empty());
}

TEST(FarField, RejectsBadSettingsNamingTheSource) {
  auto rejects = [](FarFieldSettings s, const char* what) {
    try {
      checkFarFieldSettings(s, "run.json");
      ADD_FAILURE() << "accepted " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("run.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  FarFieldSettings s;
  s.count = -1;
  rejects(s, "count");
  s = {};
  s.opacity = 1.0f;
  rejects(s, "opacity");
  s = {};
  s.sigmaFactor = 0.0f;
  rejects(s, "sigma_factor");
  s = {};
  s.truncation = NAN;
  rejects(s, "truncation");
  s = {};
  s.boxes.push_back({Vec3f(0.0f), Vec3f(1.0f, 1.0f, 0.0f), 10});
  rejects(s, "far_field.boxes[0]: min must be below max");
  s.boxes[0].max.z = 1.0f;
  s.boxes[0].count = 0;
  rejects(s, "far_field.boxes[0]: count");
}

}  // namespace
}  // namespace glint
