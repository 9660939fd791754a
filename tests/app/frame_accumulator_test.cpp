// The viewer's accumulation and display mapping: means of samples, exposure before the
// filmic tonemap, the denoise toggle smoothing noise of the final image only, and the
// per-bounce modes adding up to the specular one.
#include "app/viewer/frame_accumulator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/tonemap.h"
#include "math/rng.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_layers.h"
#include "render/gaussian_renderer.h"

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

// Accumulated as the viewer does (one jittered sample per pass), the bounce modes of a view
// between two facing mirrors sum to its specular mode, and each shows light of its own.
TEST(FrameAccumulator, BounceModesSumToTheSpecularMode) {
  GaussianScene scene = test::facingMirrors();
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings());
  Camera camera =
      Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0.3, -0.4, 1.5), Vec3d(0, 0, 0), Vec3d(0, 0, 1)), 0.9, 16, 12);
  RenderSettings render;
  render.path.bounces = 3;
  FrameAccumulator acc;
  acc.reset(camera.width, camera.height, render.path.bounces);
  for (int sample = 0; sample < 4; ++sample) {
    render.firstSample = sample;
    std::vector<Image> bounceLight;
    ViewBuffers buffers = renderGaussianView(*tracer, camera, render, 0, &bounceLight);
    ASSERT_EQ(bounceLight.size(), 3u);
    acc.add(buffers, bounceLight);
  }

  Image specular = acc.mean(Buffer::Specular);
  Image sum(camera.width, camera.height, 3);
  for (int k = 1; k <= 3; ++k) {
    Image bounce = acc.meanBounce(k);
    float brightest = 0;
    for (size_t i = 0; i < sum.pixels.size(); ++i) {
      sum.pixels[i] += bounce.pixels[i];
      brightest = std::max(brightest, bounce.pixels[i]);
    }
    EXPECT_GT(brightest, 0.01f) << "bounce " << k << " shows no light";
  }
  // Equal up to the order of float additions (per bounce over samples, or per sample over bounces).
  for (size_t i = 0; i < sum.pixels.size(); ++i)
    ASSERT_NEAR(sum.pixels[i], specular.pixels[i], 1e-5f * std::abs(specular.pixels[i]) + 1e-7f) << i;

  // Shown as radiance, like the specular mode; a bounce not accumulated is black.
  DisplaySettings settings;
  settings.mode = Buffer::Specular;
  settings.bounce = 2;
  EXPECT_NEAR(acc.display(settings).rgb(8, 6).x, tonemapFilmic(acc.meanBounce(2).rgb(8, 6).x), 1e-6f);
  settings.bounce = 4;
  for (float v : acc.display(settings).pixels) ASSERT_EQ(v, tonemapFilmic(0.0f));
}

}  // namespace
}  // namespace glint
