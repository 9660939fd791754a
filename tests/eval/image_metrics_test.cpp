// Tests of PSNR, SSIM (against a direct, non-separable reference), the tonemapped 8-bit
// versions, depth RMSE and normal angular error.
#include "eval/image_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "io/tonemap.h"
#include "math/rng.h"
#include "scene/buffers.h"

namespace glint {
namespace {

Image randomImage(int width, int height, int channels, uint64_t seed, float scale = 1.0f) {
  Image image(width, height, channels);
  Rng rng = Rng::forKeys({seed});
  for (float& v : image.pixels) v = scale * rng.uniform();
  return image;
}

// SSIM straight from Wang et al. 2004: at every pixel where the 11x11 window fits, the
// window's weights are evaluated in 2D and the moments summed directly.
double referenceSsim(const Image& a, const Image& b) {
  const double sigma = 1.5, c1 = 1e-4, c2 = 9e-4;
  double weights[11][11], total = 0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) {
      weights[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * sigma * sigma));
      total += weights[i][j];
    }
  double channelSum = 0;
  for (int c = 0; c < a.channels; ++c) {
    double mapSum = 0;
    int count = 0;
    for (int y0 = 0; y0 + 11 <= a.height; ++y0)
      for (int x0 = 0; x0 + 11 <= a.width; ++x0) {
        double muX = 0, muY = 0;
        for (int i = 0; i < 11; ++i)
          for (int j = 0; j < 11; ++j) {
            double w = weights[i][j] / total;
            muX += w * a.at(x0 + j, y0 + i, c);
            muY += w * b.at(x0 + j, y0 + i, c);
          }
        double varX = 0, varY = 0, cov = 0;
        for (int i = 0; i < 11; ++i)
          for (int j = 0; j < 11; ++j) {
            double w = weights[i][j] / total;
            double dx = a.at(x0 + j, y0 + i, c) - muX, dy = b.at(x0 + j, y0 + i, c) - muY;
            varX += w * dx * dx;
            varY += w * dy * dy;
            cov += w * dx * dy;
          }
        mapSum += ((2 * muX * muY + c1) * (2 * cov + c2)) / ((muX * muX + muY * muY + c1) * (varX + varY + c2));
        ++count;
      }
    channelSum += mapSum / count;
  }
  return channelSum / a.channels;
}

TEST(ImageMetricsTest, IdenticalImagesHaveInfinitePsnrAndSsimOne) {
  Image a = randomImage(20, 16, 3, 1, 3.0f);
  EXPECT_EQ(psnr(a, a), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
  EXPECT_EQ(psnrTonemapped8Bit(a, a), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(ssimTonemapped8Bit(a, a), 1.0, 1e-12);
}

TEST(ImageMetricsTest, PsnrOfAKnownErrorIsExact) {
  // Every value off by 0.1: MSE = 0.01, PSNR = 20 dB, whatever the values (range stays 1
  // even above 1).
  Image a = randomImage(7, 5, 3, 2, 4.0f), b = a;
  for (float& v : b.pixels) v += 0.1f;
  EXPECT_NEAR(psnr(a, b), 20.0, 1e-4);
  // Half the values off by 0.2, half exact: MSE = 0.02.
  Image c(4, 1, 1, 0.5f), d = c;
  d.at(0, 0) += 0.2f, d.at(2, 0) -= 0.2f;
  EXPECT_NEAR(psnr(c, d), 10.0 * std::log10(1.0 / 0.02), 1e-5);
}

TEST(ImageMetricsTest, SsimMatchesTheDirectReferenceOnRandomImages) {
  for (int channels : {1, 3}) {
    Image a = randomImage(23, 17, channels, 10 + channels);
    Image b = a;
    Rng rng = Rng::forKeys({99, uint64_t(channels)});
    for (float& v : b.pixels) v = 0.7f * v + 0.3f * rng.uniform();
    double fast = ssim(a, b), reference = referenceSsim(a, b);
    EXPECT_NEAR(fast, reference, 1e-9) << channels;
    EXPECT_GT(fast, 0.0);
    EXPECT_LT(fast, 1.0);
    // Two unrelated images as well.
    Image c = randomImage(23, 17, channels, 50 + channels);
    EXPECT_NEAR(ssim(a, c), referenceSsim(a, c), 1e-9) << channels;
  }
  // The smallest image the window fits in: one map value.
  Image a = randomImage(11, 11, 1, 3), b = randomImage(11, 11, 1, 4);
  EXPECT_NEAR(ssim(a, b), referenceSsim(a, b), 1e-9);
}

TEST(ImageMetricsTest, SsimOfOffsetAndNoiseIsBelowOneAndSymmetric) {
  Image a = randomImage(32, 24, 3, 5);
  Image offset = a;
  for (float& v : offset.pixels) v += 0.2f;
  Image noisy = a;
  Rng rng = Rng::forKeys({6});
  for (float& v : noisy.pixels) v += 0.1f * (rng.uniform() - 0.5f);
  for (const Image* b : {&offset, &noisy}) {
    double s = ssim(a, *b);
    EXPECT_LT(s, 1.0);
    EXPECT_GT(s, 0.5);  // both keep the structure
    EXPECT_DOUBLE_EQ(s, ssim(*b, a));
  }
  // More noise, lower SSIM.
  Image noisier = a;
  for (float& v : noisier.pixels) v += 0.5f * (rng.uniform() - 0.5f);
  EXPECT_LT(ssim(a, noisier), ssim(a, noisy));
}

TEST(ImageMetricsTest, TonemappedVersionQuantisesTheFilmicCurve) {
  Image linear(3, 1, 1);
  linear.at(0, 0) = 0.0f, linear.at(1, 0) = 0.3f, linear.at(2, 0) = 100.0f;
  Image eight = tonemapTo8Bit(linear);
  for (int x = 0; x < 3; ++x) {
    float v = eight.at(x, 0);
    EXPECT_FLOAT_EQ(v * 255.0f, std::round(v * 255.0f));
    EXPECT_NEAR(v, tonemapFilmic(linear.at(x, 0)), 0.5f / 255.0f + 1e-6f);
  }
  // Differences below one 8-bit step vanish; the linear metric still sees them.
  Image a(12, 12, 3, 0.5f), b = a;
  b.at(3, 3, 1) += 1e-5f;
  EXPECT_EQ(psnrTonemapped8Bit(a, b), std::numeric_limits<double>::infinity());
  EXPECT_LT(psnr(a, b), std::numeric_limits<double>::infinity());
  // Bright values (x = 5 and 6) differ by 1 in linear space but by little once tonemapped.
  Image bright(12, 12, 3, 5.0f), brighter(12, 12, 3, 6.0f);
  EXPECT_NEAR(psnr(bright, brighter), 0.0, 1e-9);
  EXPECT_GT(psnrTonemapped8Bit(bright, brighter), 30.0);
}

// A display-referred dataset's 8-bit figures use its own transfer (sRGB for NeRF-synthetic);
// the default stays the paper's filmic curve.
TEST(ImageMetricsTest, EightBitImagesFollowTheDisplayTransfer) {
  Image linear(4, 1, 1);
  linear.at(0, 0) = 0.0f, linear.at(1, 0) = 0.05f, linear.at(2, 0) = 0.5f, linear.at(3, 0) = 3.0f;
  const Image srgb = tonemapTo8Bit(linear, Transfer::Srgb), filmic = tonemapTo8Bit(linear);
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(srgb.at(x, 0), std::round(std::clamp(toDisplay(Transfer::Srgb, linear.at(x, 0)), 0.0f, 1.0f) * 255.0f) / 255.0f);
    EXPECT_EQ(filmic.at(x, 0), std::round(tonemapFilmic(linear.at(x, 0)) * 255.0f) / 255.0f);
  }
  EXPECT_EQ(srgb.at(3, 0), 1.0f);  // above 1 clips, as an 8-bit sRGB file does
  EXPECT_NE(srgb.at(1, 0), filmic.at(1, 0));
  Image a(12, 12, 3, 0.2f), b(12, 12, 3, 0.25f);
  EXPECT_NE(psnrTonemapped8Bit(a, b, Transfer::Srgb), psnrTonemapped8Bit(a, b));
}

TEST(ImageMetricsTest, DepthRmseCountsOnlyGroundTruthSurfaces) {
  Image truth(4, 1, 1), predicted(4, 1, 1);
  truth.pixels = {2.0f, 0.0f, 3.0f, 2.0e9f};  // pixels 1 and 3 have no surface
  predicted.pixels = {2.5f, 7.0f, 0.0f, 1.0f};
  // Errors 0.5 and 3 (nothing rendered at a true surface counts in full).
  EXPECT_NEAR(depthRmse(predicted, truth), std::sqrt((0.25 + 9.0) / 2.0), 1e-12);
  Image empty(2, 2, 1, 0.0f);
  EXPECT_TRUE(std::isnan(depthRmse(empty, empty)));
}

TEST(ImageMetricsTest, NormalAngleMasksByTruthAndCountsMissingNormalsAsNinetyDegrees) {
  Image truthNormal(4, 1, 3), predicted(4, 1, 3), truthDepth(4, 1, 1, 1.0f);
  truthNormal.setRgb(0, 0, {0, 0, 1});
  predicted.setRgb(0, 0, {0, 2, 2});  // 45 degrees, not unit length
  truthNormal.setRgb(1, 0, {1, 0, 0});
  predicted.setRgb(1, 0, {0, 0, 0});  // nothing rendered: 90 degrees
  truthNormal.setRgb(2, 0, {0, 1, 0});
  predicted.setRgb(2, 0, {0, -1, 0});  // opposite: 180 degrees
  truthNormal.setRgb(3, 0, {0, 1, 0});
  predicted.setRgb(3, 0, {1, 0, 0});
  truthDepth.at(3, 0) = 0.0f;  // background: ignored
  EXPECT_NEAR(normalAngleDegrees(predicted, truthNormal, truthDepth), (45.0 + 90.0 + 180.0) / 3.0, 1e-9);
  // Identical normals: exactly zero, even off the axes.
  Image n(1, 1, 3), d(1, 1, 1, 1.0f);
  n.setRgb(0, 0, normalize(Rgb(0.3f, -0.5f, 0.8f)));
  EXPECT_NEAR(normalAngleDegrees(n, n, d), 0.0, 1e-5);
  d.at(0, 0) = 0.0f;
  EXPECT_TRUE(std::isnan(normalAngleDegrees(n, n, d)));
}

TEST(ImageMetricsTest, MismatchedImagesAreRejected) {
  Image rgb(16, 12, 3), gray(16, 12, 1), small(12, 12, 3), tiny(8, 6, 3);
  EXPECT_THROW(psnr(rgb, gray), Error);
  EXPECT_THROW(psnr(rgb, small), Error);
  EXPECT_THROW(ssim(rgb, small), Error);
  EXPECT_THROW(ssim(tiny, tiny), Error);  // smaller than the window
  EXPECT_THROW(psnrTonemapped8Bit(rgb, gray), Error);
  EXPECT_THROW(depthRmse(rgb, rgb), Error);
  EXPECT_THROW(depthRmse(gray, Image(12, 12, 1)), Error);
  EXPECT_THROW(normalAngleDegrees(rgb, rgb, Image(12, 12, 1)), Error);
  EXPECT_THROW(normalAngleDegrees(gray, rgb, gray), Error);
}

}  // namespace
}  // namespace glint
