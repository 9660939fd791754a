// Degradations: the statistics of what each one does, and determinism given the seed.
#include "scene/buffer_degradation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

double angleBetween(const Vec3d& a, const Vec3d& b) {
  return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0, 1.0));
}

// A tilted plane's normals, with a band of "no surface" (zero) pixels.
Image planeNormals(int w, int h) {
  Image n(w, h, 3);
  Vec3d up = normalize(Vec3d(0.2, 0.9, 0.3));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (j >= 4) n.setRgb(i, j, Rgb(up));
  return n;
}

TEST(GaussianBlur, KeepsConstantsAndSpreadsAnImpulseBySigma) {
  Image flat(20, 10, 3, 0.7f);
  Image blurredFlat = gaussianBlur(flat, 2.0);
  for (float v : blurredFlat.pixels) EXPECT_NEAR(v, 0.7f, 1e-6f);

  Image impulse(41, 41, 1);
  impulse.at(20, 20) = 1.0f;
  Image spread = gaussianBlur(impulse, 3.0);
  double sum = 0, secondMoment = 0;
  for (int j = 0; j < 41; ++j)
    for (int i = 0; i < 41; ++i) {
      sum += spread.at(i, j);
      secondMoment += spread.at(i, j) * double((i - 20) * (i - 20));
    }
  EXPECT_NEAR(sum, 1.0, 1e-5);
  EXPECT_NEAR(std::sqrt(secondMoment), 3.0, 0.1);  // truncated at 3 sigma: a little under
  EXPECT_EQ(gaussianBlur(impulse, 0.0).pixels, impulse.pixels);
}

TEST(GaussianNoise, HasTheRequestedSpreadAndRepeatsWithTheSeed) {
  Image zero(100, 100, 2);
  Image noisy = addGaussianNoise(zero, 0.3, 17);
  double mean = 0, square = 0;
  for (float v : noisy.pixels) mean += v, square += double(v) * v;
  mean /= noisy.pixels.size();
  double sigma = std::sqrt(square / noisy.pixels.size() - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(sigma, 0.3, 0.3 * 0.03);
  EXPECT_EQ(addGaussianNoise(zero, 0.3, 17).pixels, noisy.pixels);
  EXPECT_NE(addGaussianNoise(zero, 0.3, 18).pixels, noisy.pixels);
}

TEST(AffineDepthError, ScalesSurfacesAndKeepsBackground) {
  Image depth(3, 1, 1);
  depth.at(0, 0) = 2.0f;
  depth.at(1, 0) = 0.0f;
  depth.at(2, 0) = kNoSurfaceDepth;
  Image out = affineDepthError(depth, 1.1, -0.3);
  EXPECT_FLOAT_EQ(out.at(0, 0), 1.9f);
  EXPECT_EQ(out.at(1, 0), 0.0f);
  EXPECT_EQ(out.at(2, 0), kNoSurfaceDepth);
  EXPECT_EQ(affineDepthError(depth, 0.1, -5.0).at(0, 0), 0.0f);  // pushed behind the camera: no surface
}

// Mean tilt angle between two normal maps over the non-zero normals.
double meanTilt(const Image& before, const Image& after, double* maxLengthError) {
  double sum = 0;
  int count = 0;
  *maxLengthError = 0;
  for (int j = 0; j < before.height; ++j)
    for (int i = 0; i < before.width; ++i) {
      Vec3d a(before.rgb(i, j)), b(after.rgb(i, j));
      if (length(a) == 0) {
        EXPECT_EQ(length(b), 0.0);
        continue;
      }
      *maxLengthError = std::max(*maxLengthError, std::abs(length(b) - 1.0));
      sum += angleBetween(a, b);
      ++count;
    }
  return sum / count;
}

TEST(PerturbNormals, MeanTiltMatchesTheRequestPerPixelAndSmooth) {
  Image normals = planeNormals(96, 96);
  const double requested = 3.0 * 3.14159265358979323846 / 180.0;
  for (double correlation : {0.0, 2.0}) {
    Image tilted = perturbNormals(normals, requested, 5, correlation);
    double lengthError = 0;
    double mean = meanTilt(normals, tilted, &lengthError);
    EXPECT_NEAR(mean, requested, 0.1 * requested) << "correlation " << correlation;
    EXPECT_LT(lengthError, 1e-5);
    EXPECT_EQ(perturbNormals(normals, requested, 5, correlation).pixels, tilted.pixels);
  }
}

TEST(PerturbNormals, SmoothTiltsVaryLittleBetweenNeighbours) {
  Image normals = planeNormals(64, 64);
  const double requested = 0.05;
  auto neighbourAngle = [](const Image& n) {
    double sum = 0;
    int count = 0;
    for (int j = 8; j < 64; ++j)
      for (int i = 0; i + 1 < 64; ++i, ++count) sum += angleBetween(Vec3d(n.rgb(i, j)), Vec3d(n.rgb(i + 1, j)));
    return sum / count;
  };
  double white = neighbourAngle(perturbNormals(normals, requested, 9, 0.0));
  double smooth = neighbourAngle(perturbNormals(normals, requested, 9, 4.0));
  EXPECT_GT(white, 1.0 * requested);  // independent tilts: neighbours differ by about the tilt
  EXPECT_LT(smooth, 0.3 * requested);
}

TEST(BiasRoughness, ScalesOffsetsAndClamps) {
  Image r(3, 1, 1);
  r.at(0, 0) = 0.5f;
  r.at(1, 0) = 0.95f;
  r.at(2, 0) = 0.02f;
  Image out = biasRoughness(r, 1.2, -0.05);
  EXPECT_FLOAT_EQ(out.at(0, 0), 0.55f);
  EXPECT_FLOAT_EQ(out.at(1, 0), 1.0f);
  EXPECT_FLOAT_EQ(out.at(2, 0), 0.0f);
}

TEST(DegradeBuffers, CombinesTheDegradationsAndKeepsBackground) {
  ViewBuffers exact = ViewBuffers::allocate(32, 32);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      bool surface = i < 24;
      exact[Buffer::Depth].at(i, j) = surface ? 2.0f + 0.01f * i : 0.0f;
      if (surface) exact[Buffer::Normal].setRgb(i, j, Rgb(0, 0, 1));
      exact[Buffer::Roughness].at(i, j) = 0.4f;
      exact[Buffer::Render].setRgb(i, j, Rgb(0.3f));
    }
  BufferDegradation g;
  g.blurSigma = 1.5;
  g.depthScale = 1.2, g.depthOffset = 0.1;
  g.normalMeanAngle = 0.05, g.normalCorrelation = 2.0;
  g.roughnessScale = 1.5, g.roughnessOffset = 0.0;
  g.seed = 3;
  ViewBuffers out = degradeBuffers(exact, g, 7);
  // Background stays background; the blur never mixes it into surfaces.
  EXPECT_EQ(out[Buffer::Depth].at(28, 5), 0.0f);
  EXPECT_EQ(length(out[Buffer::Normal].rgb(28, 5)), 0.0f);
  EXPECT_NEAR(out[Buffer::Depth].at(23, 5), 1.2f * (2.0f + 0.01f * 23) + 0.1f, 0.03f);
  EXPECT_NEAR(out[Buffer::Depth].at(10, 5), 1.2f * 2.1f + 0.1f, 1e-4f);  // a linear ramp survives the blur
  EXPECT_NEAR(length(out[Buffer::Normal].rgb(10, 10)), 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(out[Buffer::Roughness].at(3, 3), 0.6f);
  EXPECT_EQ(out[Buffer::Render].pixels, exact[Buffer::Render].pixels);
  // Views get independent errors; the same view repeats.
  EXPECT_NE(degradeBuffers(exact, g, 8)[Buffer::Normal].pixels, out[Buffer::Normal].pixels);
  EXPECT_EQ(degradeBuffers(exact, g, 7)[Buffer::Normal].pixels, out[Buffer::Normal].pixels);
}

}  // namespace
}  // namespace glint
