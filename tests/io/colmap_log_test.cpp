// COLMAP's progress lines and model_analyzer's figures, as COLMAP 3.8 prints them.
#include "io/colmap_log.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

void expectProgress(std::string_view line, long done, long total) {
  std::optional<ColmapProgress> progress = parseColmapProgress(line);
  ASSERT_TRUE(progress.has_value()) << line;
  EXPECT_EQ(progress->done, done) << line;
  EXPECT_EQ(progress->total, total) << line;
}

TEST(ColmapLog, ReadsEachToolsProgress) {
  expectProgress("Processed file [3/24]", 3, 24);
  expectProgress("  Processed file [24/24]", 24, 24);
  expectProgress("Matching image [5/120] in 0.512s", 5, 120);
  expectProgress("Undistorting image [4/24]", 4, 24);
  // Block i of B against block j of B: (i-1)*B + j of B*B.
  expectProgress("Matching block [1/1, 1/1] in 11.290s", 1, 1);
  expectProgress("Matching block [2/3, 1/3] in 4.0s", 4, 9);
  expectProgress("Matching block [3/3, 3/3]", 9, 9);
  expectProgress("Registering image #17 (9)", 9, 0);
}

TEST(ColmapLog, IgnoresEveryOtherLine) {
  for (std::string_view line :
       {"", "  Name:            view_0000.jpg", "Processed file", "Processed file [3/0]", "Processed file [/24]",
        "Matching block [2/3, 1/4]", "Matching block [2/3]", "Registering image #17", "Registering image #x (3)",
        "Elapsed time: 0.032 [minutes]", "Initializing with image pair #21 and #22"})
    EXPECT_FALSE(parseColmapProgress(line).has_value()) << line;
}

TEST(ColmapLog, ReadsTheModelAnalyzersFigures) {
  std::optional<ColmapModelStats> stats = parseColmapModelStats(
      "Cameras: 1\nImages: 24\nRegistered images: 23\nPoints: 988\nObservations: 3634\n"
      "Mean track length: 3.678138\nMean observations per image: 151.416667\nMean reprojection error: 0.585114px\n");
  ASSERT_TRUE(stats.has_value());
  EXPECT_EQ(stats->cameras, 1);
  EXPECT_EQ(stats->images, 24);
  EXPECT_EQ(stats->registeredImages, 23);
  EXPECT_EQ(stats->points, 988);
  EXPECT_EQ(stats->observations, 3634);
  EXPECT_DOUBLE_EQ(stats->meanTrackLength, 3.678138);
  EXPECT_DOUBLE_EQ(stats->meanReprojectionError, 0.585114);
}

TEST(ColmapLog, ReadsFiguresBehindGlogPrefixes) {
  std::optional<ColmapModelStats> stats =
      parseColmapModelStats("I20261128 01:02:03.456 123 model.cc:10] Registered images: 7\n"
                            "I20261128 01:02:03.456 123 model.cc:11] Mean reprojection error: 1.25px\n");
  ASSERT_TRUE(stats.has_value());
  EXPECT_EQ(stats->registeredImages, 7);
  EXPECT_DOUBLE_EQ(stats->meanReprojectionError, 1.25);
}

TEST(ColmapLog, MissingFiguresAreNotGuessed) {
  EXPECT_FALSE(parseColmapModelStats("").has_value());
  EXPECT_FALSE(parseColmapModelStats("Registered images: 3\n").has_value());
  EXPECT_FALSE(parseColmapModelStats("Mean reprojection error: 0.5px\nRegistered images: many\n").has_value());
}

}  // namespace
}  // namespace glint
