// Tests of per-view evaluation, averaging over views and the JSON form of metrics.json.
#include "eval/view_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "common/expect_error.h"

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

TEST(ViewMetricsTest, JsonRoundTripsAndNamesBadKeys) {
  ViewMetrics m;
  m.diffuse = {31.5, 0.91, 29.25, 0.875};
  m.specular = {std::numeric_limits<double>::quiet_NaN(), 0.5, 20, 0.25};
  m.final = {28, 0.8, 27, 0.7};
  m.depthRmse = 0.125;
  m.normalAngleDegrees = 3.5;
  ViewMetrics back = viewMetricsFromJson(toJson(m), "m.json", "mean");
  EXPECT_EQ(back.diffuse.psnrTonemapped, 29.25);
  EXPECT_EQ(back.diffuse.ssimTonemapped, 0.875);
  EXPECT_TRUE(std::isnan(back.specular.psnr));  // null
  EXPECT_EQ(back.specular.ssim, 0.5);
  EXPECT_EQ(back.final.psnr, 28);
  EXPECT_EQ(back.depthRmse, 0.125);
  EXPECT_EQ(back.normalAngleDegrees, 3.5);

  nlohmann::json j = toJson(m);
  j["final"].erase("ssim_tonemapped");
  test::expectErrorNaming([&] { viewMetricsFromJson(j, "dir/m.json", "per_view[2]"); }, "dir/m.json",
                          "per_view[2].final.ssim_tonemapped");
  j = toJson(m);
  j["depth_rmse"] = "deep";
  test::expectErrorNaming([&] { viewMetricsFromJson(j, "m.json", "mean"); }, "m.json", {"mean.depth_rmse", "not a number"});

  EXPECT_EQ(formatMetric(31.456, 2), "31.46");
  EXPECT_EQ(formatMetric(std::numeric_limits<double>::infinity(), 2), "inf");
  EXPECT_EQ(formatMetric(std::numeric_limits<double>::quiet_NaN(), 2), "-");
}

}  // namespace
}  // namespace glint
