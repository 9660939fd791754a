// Tests of per-view evaluation, averaging over views and the JSON form of metrics.json.
#include "eval/view_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace glint {
namespace {

// A view with a surface everywhere at depth 2, normals +z and uniform radiance.
ViewBuffers flatView(float radiance) {
  ViewBuffers v = ViewBuffers::allocate(12, 12);
  for (Buffer b : {Buffer::Render, Buffer::Diffuse}) v[b] = Image(12, 12, 3, radiance);
  v[Buffer::Depth] = Image(12, 12, 1, 2.0f);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) v[Buffer::Normal].setRgb(x, y, {0, 0, 1});
  return v;
}

TEST(ViewMetricsTest, EvaluatesEveryPassAndGBuffer) {
  ViewBuffers truth = flatView(0.5f), rendered = flatView(0.6f);
  rendered[Buffer::Depth] = Image(12, 12, 1, 2.5f);
  ViewMetrics m = evaluateView(rendered, truth);
  EXPECT_NEAR(m.diffuse.psnr, 20.0, 1e-4);
  EXPECT_NEAR(m.final.psnr, 20.0, 1e-4);
  EXPECT_LT(m.diffuse.ssim, 1.0);
  EXPECT_EQ(m.specular.psnr, std::numeric_limits<double>::infinity());  // both zero
  EXPECT_NEAR(m.specular.ssim, 1.0, 1e-12);
  EXPECT_NEAR(m.depthRmse, 0.5, 1e-6);
  EXPECT_NEAR(m.normalAngleDegrees, 0.0, 1e-9);
}

TEST(ViewMetricsTest, AverageSkipsViewsWhereAMetricIsUndefined) {
  ViewMetrics a, b;
  a.diffuse.psnr = 30.0, b.diffuse.psnr = 20.0;
  a.specular.psnr = std::numeric_limits<double>::infinity(), b.specular.psnr = 40.0;
  a.depthRmse = 0.1, b.depthRmse = std::numeric_limits<double>::quiet_NaN();
  a.normalAngleDegrees = b.normalAngleDegrees = std::numeric_limits<double>::quiet_NaN();
  a.final.psnr = b.final.psnr = std::numeric_limits<double>::infinity();
  std::vector<ViewMetrics> views = {a, b};
  ViewMetrics mean = averageViewMetrics(views);
  EXPECT_DOUBLE_EQ(mean.diffuse.psnr, 25.0);
  EXPECT_DOUBLE_EQ(mean.specular.psnr, 40.0);
  EXPECT_DOUBLE_EQ(mean.depthRmse, 0.1);
  EXPECT_TRUE(std::isnan(mean.normalAngleDegrees));
  EXPECT_TRUE(std::isinf(mean.final.psnr));

  // JSON has no NaN or infinity: those become null.
  nlohmann::json j = toJson(mean);
  EXPECT_DOUBLE_EQ(j["diffuse"]["psnr"].get<double>(), 25.0);
  EXPECT_TRUE(j["normal_angle_deg"].is_null());
  EXPECT_TRUE(j["final"]["psnr"].is_null());
  for (const char* key : {"psnr", "ssim", "psnr_tonemapped", "ssim_tonemapped"})
    EXPECT_TRUE(j["specular"].contains(key)) << key;
  EXPECT_TRUE(j.contains("depth_rmse"));
}

}  // namespace
}  // namespace glint
