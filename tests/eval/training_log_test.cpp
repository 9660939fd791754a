// Reading RUN/log.csv (empty fields, errors naming the line) and the curves made from it.
#include "eval/training_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/expect_error.h"
#include "eval/training_curves.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

using test::expectErrorNaming;
using test::TempFolder;

constexpr const char* kHeader =
    "step,loss,diffuse_l1,depth_l1,normal_l1,roughness_l1,f0_l1,specular_l1,gaussians,hits_per_ray,rays_per_s,wall_s,"
    "test_diffuse_psnr,test_normal_deg\n";

std::filesystem::path writeLog(const TempFolder& folder, const std::string& text) {
  std::filesystem::path path = folder / "log.csv";
  std::ofstream(path) << text;
  return path;
}

TEST(TrainingLogTest, ReadsColumnsWithEmptyFieldsAsNaN) {
  TempFolder folder;
  auto path = writeLog(folder, std::string(kHeader) +
                                   "1,0.5,0.1,0.2,0.3,0.04,0.05,0,1000,12.5,30000,0.25,,\n"
                                   "2,0.25,0.09,0.2,0.3,0.04,0.05,0.011,990,12.0,31000,0.5,28.125,3.5\r\n");
  TrainingLog log = readTrainingLog(path, {"step", "loss"});
  ASSERT_EQ(log.rows(), 2u);
  EXPECT_EQ(log.names.size(), 14u);
  EXPECT_EQ(log.column("step"), (std::vector<double>{1, 2}));
  EXPECT_EQ(log.column("gaussians")[1], 990);
  EXPECT_TRUE(std::isnan(log.column("test_diffuse_psnr")[0]));
  EXPECT_TRUE(std::isnan(log.column("test_normal_deg")[0]));  // the trailing empty field
  EXPECT_EQ(log.column("test_diffuse_psnr")[1], 28.125);
  EXPECT_EQ(log.column("test_normal_deg")[1], 3.5);
  EXPECT_TRUE(log.has("specular_l1"));
  EXPECT_FALSE(log.has("nothing"));
}

TEST(TrainingLogTest, ErrorsNameTheFileAndLine) {
  TempFolder folder;
  auto path = writeLog(folder, std::string(kHeader) + "1,0.5,0.1,0.2,0.3,0.04,0.05,0,1000,12.5,30000,0.25,,\n" +
                                   "2,0.5,0.1\n");
  expectErrorNaming([&] { readTrainingLog(path); }, path, {"line 3", "3 fields", "14"});
  path = writeLog(folder, std::string(kHeader) + "1,0.5,zero,0.2,0.3,0.04,0.05,0,1000,12.5,30000,0.25,,\n");
  expectErrorNaming([&] { readTrainingLog(path); }, path, {"line 2", "diffuse_l1", "'zero'"});
  path = writeLog(folder, "step,loss\n1,0.5\n");
  expectErrorNaming([&] { readTrainingLog(path, {"step", "gaussians"}); }, path, {"line 1", "gaussians"});
  path = writeLog(folder, "");
  expectErrorNaming([&] { readTrainingLog(path); }, path, "empty");
  expectErrorNaming([&] { readTrainingLog(folder / "none.csv"); }, folder / "none.csv", "file not found");
}

TEST(TrainingCurvesTest, RunningMeanIsCentredAndSkipsGaps) {
  std::vector<double> values = {1, 2, 3, NAN, 5, 6, 7};
  std::vector<double> mean = runningMean(values, 3);  // one value on each side
  ASSERT_EQ(mean.size(), values.size());
  EXPECT_DOUBLE_EQ(mean[0], 1.5);  // (1 + 2) / 2 at the start
  EXPECT_DOUBLE_EQ(mean[1], 2.0);
  EXPECT_DOUBLE_EQ(mean[2], 2.5);  // (2 + 3) / 2: NaN left out
  EXPECT_DOUBLE_EQ(mean[3], 4.0);  // (3 + 5) / 2
  EXPECT_DOUBLE_EQ(mean[6], 6.5);
  std::vector<double> gap = {NAN, NAN, NAN, 4};
  EXPECT_TRUE(std::isnan(runningMean(gap, 3)[0]));
  EXPECT_DOUBLE_EQ(runningMean(gap, 3)[2], 4.0);
}

TEST(TrainingCurvesTest, ChartsShowTheTermsThatHaveData) {
  TempFolder folder;
  std::string text = kHeader;
  for (int step = 1; step <= 300; ++step) {
    bool scored = step % 100 == 0;
    // specular_l1 is 0 until step 200; depth_l1 is empty throughout.
    text += std::to_string(step) + "," + std::to_string(1.0 / step) + ",0.1,,0.3,0.04,0.05," +
            (step > 200 ? "0.02" : "0") + "," + std::to_string(1000 + step) + ",12,30000," + std::to_string(step * 0.1) +
            "," + (scored ? std::to_string(20 + step / 100) : "") + "," + (scored ? "2.5" : "") + "\n";
  }
  TrainingLog log = readTrainingLog(writeLog(folder, text));
  std::vector<LineChart> charts = trainingCharts(log);
  ASSERT_EQ(charts.size(), 4u);
  EXPECT_EQ(charts[0].title, "Total loss");
  EXPECT_TRUE(charts[0].logY);
  ASSERT_EQ(charts[0].series.size(), 2u);  // raw, then its running mean
  EXPECT_LT(charts[0].series[0].opacity, 0.5);
  EXPECT_NEAR(charts[0].series[1].y[150], runningMean(log.column("loss"), kSmoothingSteps)[150], 1e-15);

  // L1 terms: diffuse, normal, roughness, f0 and specular; depth has no data.
  std::vector<std::string> labels;
  for (const ChartSeries& s : charts[1].series)
    if (!s.label.empty()) labels.push_back(s.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"diffuse_l1", "normal_l1", "roughness_l1", "f0_l1", "specular_l1"}));
  const ChartSeries& specular = charts[1].series[9];
  EXPECT_TRUE(std::isnan(specular.y[150]));  // zeros before reflections are gaps on the log axis
  EXPECT_NEAR(specular.y[250], 0.02, 1e-12);

  EXPECT_EQ(charts[2].title, "Gaussians");
  EXPECT_EQ(charts[2].series[0].y.back(), 1300);
  ASSERT_EQ(charts[3].series.size(), 1u);
  EXPECT_EQ(charts[3].series[0].x, (std::vector<double>{100, 200, 300}));
  EXPECT_EQ(charts[3].series[0].y, (std::vector<double>{21, 22, 23}));
}

}  // namespace
}  // namespace glint
