// The network-like priors differ from the exact buffers by the amounts the header states.
#include "synth/network_degradation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "synth/uniform_surface_view.h"

namespace glint {
namespace {

ViewBuffers flatNetworkView(int width, int height) {
  return test::uniformSurfaceView(width, height, normalize(Rgb(0.3f, 0.8f, 0.5f)));
}

TEST(NetworkDegradation, ParametersScaleWithWidthAndVaryPerView) {
  BufferDegradation a = networkLikeDegradation(320, 1, 0), b = networkLikeDegradation(640, 1, 0);
  EXPECT_DOUBLE_EQ(a.blurSigma, 1.0);
  EXPECT_DOUBLE_EQ(b.blurSigma, 2.0);
  EXPECT_DOUBLE_EQ(b.normalCorrelation, 2 * a.normalCorrelation);
  EXPECT_NEAR(a.normalMeanAngle * 180 / std::numbers::pi, 4.0, 1e-9);
  EXPECT_EQ(a.roughnessScale, 0.8);
  EXPECT_EQ(a.roughnessOffset, 0.1);
  for (uint64_t view = 0; view < 50; ++view) {
    BufferDegradation g = networkLikeDegradation(320, 1, view);
    EXPECT_GE(g.depthScale, 0.95);
    EXPECT_LE(g.depthScale, 1.05);
    EXPECT_GE(g.depthOffset, -0.1);
    EXPECT_LE(g.depthOffset, 0.1);
  }
  EXPECT_NE(networkLikeDegradation(320, 1, 0).depthScale, networkLikeDegradation(320, 1, 1).depthScale);
  EXPECT_NE(networkLikeDegradation(320, 1, 0).depthScale, networkLikeDegradation(320, 2, 0).depthScale);
}

TEST(NetworkDegradation, PriorsDifferByTheStatedAmountsAndThePhotoStaysExact) {
  const int width = 320, height = 240;
  ViewBuffers exact = flatNetworkView(width, height);
  const uint64_t seed = 4, view = 3;
  ViewBuffers priors = networkLikePriors(exact, seed, view);
  BufferDegradation g = networkLikeDegradation(width, seed, view);
  EXPECT_EQ(priors[Buffer::Render].pixels, exact[Buffer::Render].pixels);

  double angleSum = 0, depthSum = 0, depthSquares = 0, roughSum = 0, roughSquares = 0;
  const double n = double(width) * height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Vec3d a(exact[Buffer::Normal].rgb(x, y)), b(priors[Buffer::Normal].rgb(x, y));
      angleSum += std::acos(std::clamp(dot(a, b) / (length(a) * length(b)), -1.0, 1.0));
      double depthError = priors[Buffer::Depth].at(x, y) - (g.depthScale * 3.0 + g.depthOffset);
      depthSum += depthError, depthSquares += depthError * depthError;
      double roughError = priors[Buffer::Roughness].at(x, y) - (0.8 * 0.5 + 0.1);
      roughSum += roughError, roughSquares += roughError * roughError;
      // A uniform image blurs to itself.
      EXPECT_NEAR(priors[Buffer::Diffuse].at(x, y, 0), 0.4f, 1e-5f);
    }
  EXPECT_NEAR(angleSum / n * 180 / std::numbers::pi, 4.0, 0.4);
  EXPECT_NEAR(depthSum / n, 0.0, 0.002);  // the affine part is exactly s d + o
  EXPECT_NEAR(std::sqrt(depthSquares / n), 0.01, 0.001);
  EXPECT_NEAR(roughSum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(roughSquares / n), 0.8 * 0.03, 0.002);  // the noise is scaled with r
}

TEST(NetworkDegradation, BlursDiffuseEdges) {
  ViewBuffers exact = flatNetworkView(320, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 160; x < 320; ++x) exact[Buffer::Diffuse].setRgb(x, y, Rgb(0.0f));
  ViewBuffers priors = networkLikePriors(exact, 0, 0);
  // A step blurred with sigma 1 px: 0.4 * Phi(-0.5) = 0.123 just right of the edge.
  EXPECT_NEAR(priors[Buffer::Diffuse].at(160, 8), 0.4f * 0.3085f, 0.01f);
  EXPECT_NEAR(priors[Buffer::Diffuse].at(159, 8), 0.4f * 0.6915f, 0.01f);
}

}  // namespace
}  // namespace glint
