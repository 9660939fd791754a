// ShFit recovers known spherical-harmonics colours exactly, and averages noise as least
// squares should; the basis is orthonormal as 3DGS's constants promise.
#include "math/sh_fit.h"

#include <cmath>

#include <gtest/gtest.h>

#include "math/rng.h"
#include "math/sampling.h"
#include "math/spherical_harmonics.h"

namespace glint {
namespace {

Vec3d randomDirection(Rng& rng) { return Vec3d(sampleUniformSphere(rng.uniform2())); }
double uniformIn(Rng& rng, double a, double b) { return a + (b - a) * rng.uniformDouble(); }

Vec3d colourAt(const Vec3d& g, const std::vector<Vec3d>& rest, int degree, const Vec3d& d) {
  double b[kMaxShCoefficients];
  shBasis(d, degree, b);
  Vec3d c = g;
  for (size_t k = 0; k < rest.size(); ++k) c += rest[k] * b[k + 1];
  return c;
}

TEST(SphericalHarmonics, BasisIsOrthonormalOverTheSphere) {
  // Monte Carlo over 200k stratified directions: int B_j B_k = delta_jk within 1%.
  const int n = 200000;
  double gram[16][16] = {};
  for (int s = 0; s < n; ++s) {
    const Vec3f u = sampleUniformSphere({(float(s) + 0.5f) / n, float(std::fmod(s * 0.6180339887, 1.0))});
    double b[16];
    shBasis(Vec3d(u), 3, b);
    for (int j = 0; j < 16; ++j)
      for (int k = 0; k < 16; ++k) gram[j][k] += b[j] * b[k] * (4 * M_PI / n);
  }
  for (int j = 0; j < 16; ++j)
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(gram[j][k], j == k ? 1.0 : 0.0, 0.01) << j << "," << k;
}

TEST(SphericalHarmonics, SignsUnderAHalfTurnAboutX) {
  Rng rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3d d = randomDirection(rng);
    double b[16], turned[16];
    shBasis(d, 3, b);
    shBasis(Vec3d(d.x, -d.y, -d.z), 3, turned);
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(turned[k], kShSignUnderTurnAboutX[size_t(k)] * b[k], 1e-12) << k;
  }
}

TEST(ShFit, RecoversAKnownViewDependentColourExactly) {
  Rng rng(7);
  for (int degree = 0; degree <= 3; ++degree) {
    const Vec3d g(0.3, 0.5, 0.7);
    std::vector<Vec3d> rest(size_t(shCoefficientCount(degree) - 1));
    for (Vec3d& f : rest) f = Vec3d(uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1));
    ShFit fit(degree);
    for (int s = 0; s < 100; ++s) {
      const Vec3d d = randomDirection(rng);
      fit.add(d, colourAt(g, rest, degree, d), uniformIn(rng, 0.1, 2.0));
    }
    Vec3d constant, solved[15];
    ASSERT_TRUE(fit.solve(0.0, &constant, solved));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(constant[c], g[c], 1e-8) << "degree " << degree;
    for (size_t k = 0; k < rest.size(); ++k)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(solved[k][c], rest[k][c], 1e-8) << "degree " << degree << " k " << k;
  }
}

TEST(ShFit, NoiseAveragesOutAsLeastSquaresPredicts) {
  // y = c(d) + noise of standard deviation sigma on K uniform directions: each fitted
  // coefficient's error has variance about sigma^2 / (K / 4 pi) (the basis being orthonormal),
  // so over many coefficients the RMS error stays within a factor 1.5 of sigma sqrt(4 pi / K).
  Rng rng(11);
  const int degree = 3, K = 2000;
  const double sigma = 0.1;
  double squared = 0;
  int terms = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3d> rest(15);
    for (Vec3d& f : rest) f = Vec3d(uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1));
    ShFit fit(degree);
    for (int s = 0; s < K; ++s) {
      const Vec3d d = randomDirection(rng);
      Vec3d noise(0.0);
      for (int c = 0; c < 3; ++c) noise[c] = sigma * std::sqrt(-2 * std::log(1 - rng.uniformDouble())) *
                                                 std::cos(2 * M_PI * rng.uniformDouble());
      fit.add(d, colourAt(Vec3d(0.5), rest, degree, d) + noise, 1.0);
    }
    Vec3d constant, solved[15];
    ASSERT_TRUE(fit.solve(0.0, &constant, solved));
    for (size_t k = 0; k < 15; ++k)
      for (int c = 0; c < 3; ++c, ++terms) squared += (solved[k][c] - rest[k][c]) * (solved[k][c] - rest[k][c]);
  }
  const double rms = std::sqrt(squared / terms), predicted = sigma * std::sqrt(4 * M_PI / K);
  EXPECT_GT(rms, predicted / 1.5);
  EXPECT_LT(rms, predicted * 1.5);
}

TEST(ShFit, RidgeTurnsUndeterminedTermsToZero) {
  // One direction only: the fit is a constant colour equal to the sample.
  ShFit fit(3);
  for (int s = 0; s < 10; ++s) fit.add(Vec3d(0, 0, 1), Vec3d(0.2, 0.4, 0.6), 1.0);
  Vec3d constant, rest[15];
  ASSERT_TRUE(fit.solve(0.02, &constant, rest));
  double b[16];
  shBasis(Vec3d(0, 0, 1), 3, b);
  Vec3d atSample = constant;
  for (int k = 0; k < 15; ++k) atSample += rest[k] * b[k + 1];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(atSample[c], 0.2 * (c + 1), 0.02);
}

TEST(ShFit, NoSamplesMeansNoSolution) {
  ShFit fit(2);
  fit.add(Vec3d(0, 0, 1), Vec3d(1.0), 0.0);
  Vec3d constant, rest[8];
  EXPECT_FALSE(fit.solve(0.01, &constant, rest));
}

}  // namespace
}  // namespace glint
