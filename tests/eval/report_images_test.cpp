// Error maps and G-buffer pictures of the report: the ramp's ends and monotonic luminance,
// errors measured on the tonemapped images, depth scaled by the ground truth's surfaces.
#include "eval/report_images.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {
namespace {

TEST(ReportImages, ErrorRampRunsFromBlackToPaleYellowWithRisingLuminance) {
  EXPECT_EQ(errorRampColour(0.0f), Rgb(0.0f));
  EXPECT_EQ(errorRampColour(-1.0f), Rgb(0.0f));
  EXPECT_EQ(errorRampColour(1.0f), errorRampColour(7.0f));
  EXPECT_GT(luminance(errorRampColour(1.0f)), 0.9f);
  for (int i = 1; i <= 100; ++i)
    EXPECT_GT(luminance(errorRampColour(float(i) / 100)), luminance(errorRampColour(float(i - 1) / 100))) << i;
}

TEST(ReportImages, ErrorMapIsTheLargestTonemappedChannelDifference) {
  Image truth(3, 1, 3, 0.2f), ours = truth;
  // Pixel 1: green differs by a known amount after the tonemap; pixel 2: far beyond full scale.
  const float green = 0.5f;
  ours.at(1, 0, 1) = green;
  ours.setRgb(2, 0, Rgb(50.0f));
  Image map = errorMap(truth, ours);
  ASSERT_EQ(map.width, 3);
  ASSERT_EQ(map.channels, 3);
  EXPECT_EQ(map.rgb(0, 0), Rgb(0.0f));
  float t = (tonemapFilmic(green) - tonemapFilmic(0.2f)) / kErrorMapFullScale;
  ASSERT_GT(t, 0.1f);
  ASSERT_LT(t, 0.9f);
  Rgb expected = errorRampColour(t);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(map.at(1, 0, c), expected[c], 1e-5f);
  EXPECT_EQ(map.rgb(2, 0), errorRampColour(1.0f));
  // A smaller full scale saturates sooner.
  EXPECT_EQ(errorMap(truth, ours, 1e-3f).rgb(1, 0), errorRampColour(1.0f));
  EXPECT_THROW(errorMap(truth, Image(2, 1, 3)), Error);
}

TEST(ReportImages, DepthIsScaledByTheGroundTruthsSurfaces) {
  Image truth(4, 1, 1), ours(4, 1, 1);
  truth.pixels = {2.0f, 6.0f, 0.0f, 4.0f};  // near, far, no surface, halfway
  ours.pixels = {1.0f, 9.0f, 4.0f, kNoSurfaceDepth};
  GBufferPictures p = gBufferPictures(Buffer::Depth, truth, ours);
  EXPECT_FLOAT_EQ(p.truth.at(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(p.truth.at(1, 0), 0.15f);
  EXPECT_FLOAT_EQ(p.truth.at(2, 0), 0.0f);
  EXPECT_FLOAT_EQ(p.truth.at(3, 0), 1.0f - 0.85f * 0.5f);
  EXPECT_FLOAT_EQ(p.ours.at(0, 0), 1.0f);   // nearer than the range: clamped
  EXPECT_FLOAT_EQ(p.ours.at(1, 0), 0.15f);  // farther: clamped, still above black
  EXPECT_FLOAT_EQ(p.ours.at(2, 0), 1.0f - 0.85f * 0.5f);
  EXPECT_FLOAT_EQ(p.ours.at(3, 0), 0.0f);
  EXPECT_EQ(p.ours.channels, 3);
  EXPECT_NE(p.scale.find("depth 2 (white) to 6"), std::string::npos) << p.scale;
}

TEST(ReportImages, NormalsRoughnessAndF0AreShownInDisplayRange) {
  Image n(2, 1, 3);
  n.setRgb(0, 0, {0.0f, 0.0f, -1.0f});
  n.setRgb(1, 0, {1.0f, 0.0f, 0.0f});
  GBufferPictures normals = gBufferPictures(Buffer::Normal, n, n);
  EXPECT_EQ(normals.truth.rgb(0, 0), Rgb(0.5f, 0.5f, 0.0f));
  EXPECT_EQ(normals.ours.rgb(1, 0), Rgb(1.0f, 0.5f, 0.5f));

  Image r(2, 1, 1);
  r.pixels = {0.3f, 1.7f};
  GBufferPictures roughness = gBufferPictures(Buffer::Roughness, r, r);
  EXPECT_EQ(roughness.truth.rgb(0, 0), Rgb(0.3f));
  EXPECT_EQ(roughness.truth.rgb(1, 0), Rgb(1.0f));

  Image f0(1, 1, 3);
  f0.setRgb(0, 0, {0.95f, 0.64f, std::nanf("")});
  EXPECT_EQ(gBufferPictures(Buffer::F0, f0, f0).ours.rgb(0, 0), Rgb(0.95f, 0.64f, 0.0f));
  EXPECT_DEATH(gBufferPictures(Buffer::Render, f0, f0), "not a G-buffer");
  EXPECT_THROW(gBufferPictures(Buffer::F0, f0, Image(2, 1, 3)), Error);
}

}  // namespace
}  // namespace glint
