// Error breakdown: pixels are classed from the truth's buffers as the definitions say, the
// shares partition the error, and the noise estimate from two halves matches the variance
// of the mean of independent noise.
#include "eval/error_breakdown.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/tonemap.h"

namespace glint {
namespace {

constexpr int kW = 40, kH = 30;

// A camera at the origin looking down -z at a wall z = -4 facing it, rough everywhere.
struct WallTruth {
  Camera camera = Camera::fromFieldOfView(Mat4::identity(), 1.0, kW, kH);
  ViewBuffers truth = ViewBuffers::allocate(kW, kH);
  WallTruth() {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        Ray r = camera.generateRay(x + 0.5, y + 0.5);
        truth[Buffer::Depth].at(x, y) = float(4.0 / -r.direction.z);
        truth[Buffer::Normal].setRgb(x, y, Rgb(0.0f, 0.0f, 1.0f));
        truth[Buffer::Roughness].at(x, y) = 0.8f;
        truth[Buffer::Specular].setRgb(x, y, Rgb(0.05f));
        truth[Buffer::Render].setRgb(x, y, Rgb(0.3f));
      }
  }
  PixelKind kind(const std::vector<PixelKind>& kinds, int x, int y) const { return kinds[size_t(y) * kW + size_t(x)]; }
};

TEST(ErrorBreakdown, ClassesFollowTheTruthBuffers) {
  WallTruth w;
  // Columns 0-9: a nearer box (depth step at column 9/10), rows 0-4 no surface.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 10; ++x) w.truth[Buffer::Depth].at(x, y) *= 0.5f;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < kW; ++x) w.truth[Buffer::Depth].at(x, y) = 0.0f;
  // Columns 20-29 a mirror; its right half (25-29) curved, i.e. normals vary per column.
  for (int y = 5; y < kH; ++y)
    for (int x = 20; x < 30; ++x) {
      w.truth[Buffer::Roughness].at(x, y) = 0.02f;
      if (x >= 25) {
        double a = 0.05 * (x - 25);
        w.truth[Buffer::Normal].setRgb(x, y, Rgb(float(std::sin(a)), 0.0f, float(std::cos(a))));
      }
    }
  // Columns 32-39 glossy, with a bright highlight square at (35..37, 15..17).
  for (int y = 5; y < kH; ++y)
    for (int x = 32; x < kW; ++x) w.truth[Buffer::Roughness].at(x, y) = 0.2f;
  for (int y = 15; y <= 17; ++y)
    for (int x = 35; x <= 37; ++x) w.truth[Buffer::Specular].setRgb(x, y, Rgb(5.0f));

  std::vector<PixelKind> kinds = classifyPixels(w.camera, w.truth);
  EXPECT_EQ(w.kind(kinds, 15, 2), PixelKind::NoSurface);
  EXPECT_EQ(w.kind(kinds, 9, 15), PixelKind::Silhouette);   // beside the depth step
  EXPECT_EQ(w.kind(kinds, 10, 15), PixelKind::Silhouette);
  EXPECT_EQ(w.kind(kinds, 15, 5), PixelKind::Silhouette);   // beside the background
  EXPECT_EQ(w.kind(kinds, 5, 15), PixelKind::Rough);
  EXPECT_EQ(w.kind(kinds, 15, 15), PixelKind::Rough);
  EXPECT_EQ(w.kind(kinds, 22, 15), PixelKind::FlatMirror);
  EXPECT_EQ(w.kind(kinds, 27, 15), PixelKind::CurvedMirror);
  EXPECT_EQ(w.kind(kinds, 34, 16), PixelKind::HighlightEdge);
  EXPECT_EQ(w.kind(kinds, 36, 16), PixelKind::Glossy);  // the highlight's centre: no step around it
  EXPECT_EQ(w.kind(kinds, 33, 25), PixelKind::Glossy);

  // A grazing view: every normal perpendicular to its pixel's ray.
  WallTruth g;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      Vec3d n = normalize(cross(g.camera.generateRay(x + 0.5, y + 0.5).direction, Vec3d(1, 0, 0)));
      g.truth[Buffer::Normal].setRgb(x, y, Rgb(float(n.x), float(n.y), float(n.z)));
    }
  for (PixelKind k : classifyPixels(g.camera, g.truth)) EXPECT_EQ(k, PixelKind::Silhouette);
}

TEST(ErrorBreakdown, SharesPartitionTheErrorAndPsnrIsPerKind) {
  WallTruth w;
  for (int y = 0; y < kH; ++y)
    for (int x = 20; x < kW; ++x) w.truth[Buffer::Roughness].at(x, y) = 0.2f;  // right half glossy
  std::vector<PixelKind> kinds = classifyPixels(w.camera, w.truth);
  ViewBuffers rendered = w.truth;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) rendered[Buffer::Specular].setRgb(x, y, Rgb(x < 20 ? 0.1f : 0.3f));
  ErrorBreakdown b = breakdownView(kinds, rendered, w.truth);
  EXPECT_FALSE(b.hasNoise);
  size_t pixels = 0;
  double specular = 0;
  for (const KindError& e : b.kinds) pixels += e.pixels, specular += e.specular.squaredError;
  EXPECT_EQ(pixels, size_t(kW * kH));
  EXPECT_EQ(b[PixelKind::Rough].pixels + b[PixelKind::Glossy].pixels, size_t(kW * kH));
  EXPECT_GT(b[PixelKind::Glossy].specular.squaredError, 3 * b[PixelKind::Rough].specular.squaredError);
  EXPECT_EQ(b[PixelKind::Rough].final.squaredError, 0.0);  // the render buffer was left exact

  nlohmann::json j = toJson(b);
  double share = j["rough"]["specular_error_share"].get<double>() + j["glossy"]["specular_error_share"].get<double>();
  EXPECT_NEAR(share, 1.0, 1e-9);
  EXPECT_NEAR(j["glossy"]["pixel_share"].get<double>(), 0.5, 1e-9);
  EXPECT_TRUE(j["silhouette"]["specular_psnr_tonemapped"].is_null());  // no pixels: no PSNR

  ErrorBreakdown twice = b;
  twice += b;
  EXPECT_EQ(twice[PixelKind::Glossy].pixels, 2 * b[PixelKind::Glossy].pixels);
  EXPECT_NEAR(twice[PixelKind::Glossy].specular.psnr(), b[PixelKind::Glossy].specular.psnr(), 1e-9);
}

// Halves a and b with independent noise of standard deviation sigma around the truth: the
// estimate E(a - b)^2 / 4 should equal the variance of their mean, sigma^2 / 2, and match
// the squared error the mean actually has.
TEST(ErrorBreakdown, NoiseEstimateMatchesTheVarianceOfTheMean) {
  WallTruth w;
  std::vector<PixelKind> kinds = classifyPixels(w.camera, w.truth);
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  ViewBuffers halves[2] = {w.truth, w.truth};
  for (ViewBuffers& h : halves)
    for (Buffer buffer : {Buffer::Specular, Buffer::Render})
      for (float& v : h[buffer].pixels) v += noise(rng);
  ViewBuffers mean = w.truth;
  for (Buffer buffer : {Buffer::Specular, Buffer::Render})
    for (size_t i = 0; i < mean[buffer].pixels.size(); ++i)
      mean[buffer].pixels[i] = 0.5f * (halves[0][buffer].pixels[i] + halves[1][buffer].pixels[i]);
  ErrorBreakdown b = breakdownView(kinds, mean, w.truth, &halves[0], &halves[1]);
  ASSERT_TRUE(b.hasNoise);
  const KindError& e = b[PixelKind::Rough];
  ASSERT_EQ(e.pixels, size_t(kW * kH));
  // On the tonemapped scale the noise is scaled by the curve's slope at 0.3 (render).
  double slope = (tonemapFilmic(0.3f + 1e-3f) - tonemapFilmic(0.3f - 1e-3f)) / 2e-3;
  double expected = 0.01 * 0.01 / 2 * slope * slope;
  double estimate = e.finalNoise.squaredError / e.finalNoise.values;
  EXPECT_NEAR(estimate, expected, 0.1 * expected);  // 3600 values: about 2.4% standard error
  // The measured error of the mean is mostly that noise (plus 8-bit rounding, 1/12 of a code^2).
  double measured = e.final.squaredError / e.final.values;
  double rounding = 1.0 / (12.0 * 255.0 * 255.0);
  EXPECT_NEAR(measured, expected + rounding, 0.2 * (expected + rounding));
}

TEST(ErrorBreakdown, KindPictureHasOneColourPerKind) {
  std::vector<PixelKind> kinds = {PixelKind::Silhouette, PixelKind::FlatMirror, PixelKind::Rough, PixelKind::NoSurface};
  Image picture = pixelKindImage(kinds, 2, 2);
  EXPECT_EQ(picture.rgb(0, 0).x, pixelKindColour(PixelKind::Silhouette).x);
  EXPECT_EQ(picture.rgb(1, 0).z, pixelKindColour(PixelKind::FlatMirror).z);
  EXPECT_THROW(pixelKindImage(kinds, 3, 2), std::exception);
  EXPECT_STREQ(pixelKindName(PixelKind::HighlightEdge), "highlight edge");
}

}  // namespace
}  // namespace glint
