// The `glint info` report: tables for a valid dataset, problems for a broken one.
#include "scene/dataset_summary.h"

#include <gtest/gtest.h>

#include "io/temp_folder.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::TempFolder;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(DatasetSummary, DescribesAValidDataset) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  bool clean = false;
  std::string report = describeDataset(folder.path(), &clean);
  EXPECT_TRUE(clean);
  EXPECT_TRUE(contains(report, "8x6")) << report;
  EXPECT_TRUE(contains(report, "40.11")) << report;  // 0.7 rad
  EXPECT_TRUE(contains(report, "train buffers, over all 2 views")) << report;
  EXPECT_TRUE(contains(report, "test buffers, over all 1 view")) << report;
  EXPECT_TRUE(contains(report, "roughness")) << report;
  // Depth: column 0 (6 pixels) and pixel (7, 0) have no surface: 7 of 48.
  EXPECT_TRUE(contains(report, "no surface in 14.6%")) << report;
  EXPECT_TRUE(contains(report, "point_cloud_dense.ply, 10 points")) << report;
  EXPECT_TRUE(contains(report, "problems: none")) << report;
}

TEST(DatasetSummary, SamplesLargeSplitsAndCapsTheProblemList) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path(), ImageFormat::Exr, 25, 1, false);
  for (const char* buffer : {"normal", "roughness", "f0"}) fs::remove_all(folder / "train" / buffer);
  bool clean = true;
  std::string report = describeDataset(folder.path(), &clean);
  EXPECT_FALSE(clean);
  EXPECT_TRUE(contains(report, "train buffers, over 20 of 25 views (evenly spaced)")) << report;
  EXPECT_TRUE(contains(report, "20 unreadable (see problems)")) << report;
  EXPECT_TRUE(contains(report, "point cloud: none")) << report;
  EXPECT_TRUE(contains(report, "problems: 75")) << report;
  EXPECT_TRUE(contains(report, "... and 25 more")) << report;
  // Problem files are shown relative to the dataset folder.
  EXPECT_TRUE(contains(report, "\n  train/normal/normal_0000: normal buffer not found")) << report;
}

TEST(DatasetSummary, ReportsUnreadableTransformsWithoutThrowing) {
  TempFolder folder;
  bool clean = true;
  std::string report = describeDataset(folder.path(), &clean);
  EXPECT_FALSE(clean);
  EXPECT_TRUE(contains(report, "no transforms file: no such split")) << report;
  EXPECT_TRUE(contains(report, "transforms_train.json: file not found")) << report;
  EXPECT_TRUE(contains(report, "transforms_test.json: file not found")) << report;
}

}  // namespace
}  // namespace glint
