// The viewer's accumulation and display mapping: means of samples, exposure before the
// filmic tonemap, and the denoise toggle smoothing noise of the final image only.
#include "app/viewer/frame_accumulator.h"

#include <gtest/gtest.h>

#include "io/tonemap.h"
#include "math/rng.h"

namespace glint {
namespace {

ViewBuffers constantView(int w, int h, float radiance) {
  ViewBuffers v = ViewBuffers::allocate(w, h);
  for (float& x : v[Buffer::Render].pixels) x = radiance;
  for (float& x : v[Buffer::Diffuse].pixels) x = 0.5f;
  for (float& x : v[Buffer::Depth].pixels) x = 2.0f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) v[Buffer::Normal].setRgb(x, y, Rgb(0, 0, 1));
  return v;
}

TEST(FrameAccumulator, ShowsTheMeanThroughExposureAndTonemap) {
  FrameAccumulator acc;
  acc.reset(4, 3);
  acc.add(constantView(4, 3, 0.2f));
  acc.add(constantView(4, 3, 0.6f));
  EXPECT_EQ(acc.samples(), 2);
  DisplaySettings settings;
  settings.exposure = 1;  // x2
  Image shown = acc.display(settings);
  EXPECT_NEAR(shown.at(2, 1, 0), tonemapFilmic(0.8f), 1e-6f);
  settings.mode = Buffer::Normal;
  EXPECT_NEAR(acc.display(settings).at(0, 0, 2), 1.0f, 1e-6f);  // n/2 + 1/2 of +z
}

TEST(FrameAccumulator, DenoiseSmoothsTheFinalImage) {
  FrameAccumulator acc;
  acc.reset(32, 24);
  ViewBuffers noisy = constantView(32, 24, 0.5f);
  Rng rng(3);
  for (float& x : noisy[Buffer::Render].pixels) x = 0.5f + 0.4f * (rng.uniform() - 0.5f);
  acc.add(noisy);
  auto variance = [](const Image& image) {
    double sum = 0, sumSquares = 0;
    for (float x : image.pixels) sum += x, sumSquares += double(x) * x;
    double n = double(image.pixels.size());
    return sumSquares / n - (sum / n) * (sum / n);
  };
  DisplaySettings settings;
  double raw = variance(acc.display(settings));
  settings.denoise = true;
  double denoised = variance(acc.display(settings));
  EXPECT_LT(denoised, 0.25 * raw);
  settings.mode = Buffer::Diffuse;  // other modes are shown as they are
  Image diffuseDenoised = acc.display(settings);
  settings.denoise = false;
  EXPECT_EQ(diffuseDenoised.pixels, acc.display(settings).pixels);
}

}  // namespace
}  // namespace glint
