// The monocular priors differ from the exact buffers by the amounts the header states, and
// their depth is not an affine function of the truth.
#include "synth/monocular_degradation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io/transfer.h"
#include "synth/uniform_surface_view.h"

namespace glint {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

ViewBuffers flatView(int width, int height) {
  return test::uniformSurfaceView(width, height, Rgb(0.0f, 0.0f, 1.0f));
}

TEST(MonocularDegradation, ParametersScaleWithWidthAndVaryPerView) {
  MonocularDegradation a = monocularDegradation(160, 1, 0), b = monocularDegradation(320, 1, 0);
  EXPECT_DOUBLE_EQ(a.radianceBlur, 0.7);
  EXPECT_DOUBLE_EQ(b.radianceBlur, 1.4);
  EXPECT_DOUBLE_EQ(b.depthFieldCorrelation, 2 * a.depthFieldCorrelation);
  EXPECT_NEAR(a.normalMeanAngle / kDegree, 3.0, 1e-12);
  EXPECT_NEAR(a.normalViewTilt / kDegree, 1.5, 1e-12);
  for (uint64_t view = 0; view < 50; ++view) {
    double gamma = monocularDegradation(160, 1, view).depthGamma;
    EXPECT_GE(gamma, 0.85);
    EXPECT_LE(gamma, 1.15);
  }
  EXPECT_NE(monocularDegradation(160, 1, 0).depthGamma, monocularDegradation(160, 1, 1).depthGamma);
}

TEST(MonocularDegradation, PriorsDifferByTheStatedAmountsAndThePhotoStaysExact) {
  const int width = 160, height = 120;
  const ViewBuffers exact = flatView(width, height);
  const ViewBuffers priors = monocularPriors(exact, 4, 3);
  EXPECT_EQ(priors[Buffer::Render].pixels, exact[Buffer::Render].pixels);
  EXPECT_EQ(priors[Buffer::F0].pixels, exact[Buffer::F0].pixels);  // the writer makes it metalness

  const double n = double(width) * height;
  double angleSum = 0, depthSum = 0, depthSquares = 0, roughSum = 0, roughSquares = 0, displaySquares = 0;
  Vec3d meanNormal(0.0);
  const float trueDisplay = toDisplay(Transfer::Filmic, 0.4f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Vec3d b(priors[Buffer::Normal].rgb(x, y));
      meanNormal += b;
      angleSum += std::acos(std::clamp(b.z / length(b), -1.0, 1.0));
      double depthError = priors[Buffer::Depth].at(x, y) / 3.0 - 1.0;
      depthSum += depthError, depthSquares += depthError * depthError;
      double roughError = priors[Buffer::Roughness].at(x, y) - 0.55;
      roughSum += roughError, roughSquares += roughError * roughError;
      double displayError = toDisplay(Transfer::Filmic, priors[Buffer::Diffuse].at(x, y, 0)) - trueDisplay;
      displaySquares += displayError * displayError;
    }
  // The shared tilt survives averaging; the per-pixel noise does not.
  EXPECT_NEAR(std::acos(normalize(meanNormal).z) / kDegree, 1.5, 0.3);
  EXPECT_NEAR(angleSum / n / kDegree, std::hypot(3.0, 1.5), 0.8);
  // The 4% field (correlated over 12 px: few independent samples) and 0.5% noise.
  EXPECT_NEAR(depthSum / n, 0.0, 0.02);
  EXPECT_NEAR(std::sqrt(depthSquares / n), std::hypot(0.04, 0.005), 0.015);
  EXPECT_NEAR(roughSum / n, 0.0, 0.003);
  EXPECT_NEAR(std::sqrt(roughSquares / n), 0.05, 0.004);
  EXPECT_NEAR(std::sqrt(displaySquares / n), kRadianceNoise, 0.2 * kRadianceNoise);
}

// The least-squares affine fit of degraded against true depth over a ramp from 1 to 6 m
// leaves residuals far above the noise in views whose warp is not the identity: no
// per-view affine alignment undoes it.
TEST(MonocularDegradation, DepthIsNotAffineInTheTruth) {
  const int width = 160, height = 120;
  ViewBuffers exact = flatView(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) exact[Buffer::Depth].at(x, y) = float(1.0 + 5.0 * x / (width - 1));
  double worst = 0;
  for (uint64_t view = 0; view < 8; ++view) {
    const Image d = monocularPriors(exact, 0, view)[Buffer::Depth];
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (size_t p = 0; p < d.pixels.size(); ++p) {
      double x = exact[Buffer::Depth].pixels[p], y = d.pixels[p];
      sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
    }
    double a = (n * sxy - sx * sy) / (n * sxx - sx * sx), b = (sy - a * sx) / n;
    // Mean |residual| over the two ends of the ramp, where a power curve leaves its chord.
    double ends = 0;
    int count = 0;
    for (int y = 0; y < height; ++y)
      for (int x : {0, 1, width - 2, width - 1}) {
        double truth = exact[Buffer::Depth].at(x, y);
        ends += std::abs(d.at(x, y) - (a * truth + b)) / truth, ++count;
      }
    worst = std::max(worst, ends / count);
  }
  EXPECT_GT(worst, 0.03);
}

}  // namespace
}  // namespace glint
