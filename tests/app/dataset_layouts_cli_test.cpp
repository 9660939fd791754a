// Datasets as people have them, end to end: a NeRF-synthetic folder (final images only)
// trains the RGB-only baseline and evaluates; --downscale; a dataset holding one split
// renders and evaluates it; and a failed start leaves nothing that blocks the retry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "app/small_cloud.h"
#include "io/image.h"
#include "io/json_file.h"
#include "io/temp_folder.h"
#include "scene/nerf_synthetic_files.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

class DatasetLayoutsCliTest : public ::testing::Test {
 protected:
  // 16x12 RGBA views: four to train on, and transforms_val.json as the test split.
  static void SetUpTestSuite() {
    folder_ = new test::TempFolder;
    test::writeNerfSyntheticDataset(*folder_ / "N", {{"train", 4}, {"val", 2}});
  }
  static void TearDownTestSuite() { delete folder_; }
  static std::string path(const std::string& name) { return (*folder_ / name).string(); }
  static test::TempFolder* folder_;
};

test::TempFolder* DatasetLayoutsCliTest::folder_ = nullptr;

const char* kTinyRun = " --iters 10 --batch-rays 256 --threads 2 --eval-views 1 --eval-every 5";

TEST_F(DatasetLayoutsCliTest, NerfSyntheticTrainsTheRgbBaselineAndEvaluates) {
  Outcome info = runGlint("info " + path("N"));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("transforms_val.json as the test split"), std::string::npos) << info.output;

  Outcome train = runGlint("train " + path("N") + " -o " + path("R") + kTinyRun);
  ASSERT_EQ(train.status, 0) << train.output;
  EXPECT_NE(train.output.find("has final images only"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("training the RGB-only baseline"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("at random in the volume the cameras look at"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("shell in the background colour"), std::string::npos) << train.output;
  const nlohmann::json config = readJsonFile(path("R") + "/config.json");
  EXPECT_EQ(config["baseline"], "rgb");
  EXPECT_EQ(config["background"], "white");
  EXPECT_TRUE(fs::exists(path("R") + "/scene.ply"));

  Outcome eval = runGlint("eval " + path("R") + " --spp 1 --threads 2");
  ASSERT_EQ(eval.status, 0) << eval.output;
  const nlohmann::json metrics = readJsonFile(path("R") + "/eval/metrics.json");
  EXPECT_EQ(metrics["views"], 2);
  EXPECT_EQ(metrics["background"], "white");
  // NeRF-synthetic images are sRGB: the 8-bit figures are on sRGB images, as published
  // methods score them, and the table says so.
  EXPECT_EQ(metrics["display_transfer"], "srgb");
  EXPECT_NE(eval.output.find("8-bit = srgb, quantised"), std::string::npos) << eval.output;

  Outcome render = runGlint("render " + path("R") + " --split test -o " + path("out") + " --threads 1");
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_TRUE(fs::exists(path("out") + "/render/render_r_1.exr")) << render.output;

  // Black: the shell is not needed (a ray leaving the Gaussians is black already).
  Outcome black = runGlint("train " + path("N") + " -o " + path("B") + " --background black --iters 2 --threads 2");
  ASSERT_EQ(black.status, 0) << black.output;
  EXPECT_EQ(readJsonFile(path("B") + "/config.json")["background"], "black");
  EXPECT_EQ(black.output.find("shell"), std::string::npos) << black.output;
}

TEST_F(DatasetLayoutsCliTest, DownscaleShrinksTrainingEvalAndRenderViews) {
  // 64x48 views: SSIM's 11x11 window still fits at 1/4.
  test::writeNerfSyntheticDataset(path("N64"), {{"train", 4}, {"test", 2}}, 64, 48);
  Outcome train = runGlint("train " + path("N64") + " -o " + path("D2") + " --downscale 2" + kTinyRun);
  ASSERT_EQ(train.status, 0) << train.output;
  EXPECT_NE(train.output.find("(the first 32x24)"), std::string::npos) << train.output;
  EXPECT_EQ(readJsonFile(path("D2") + "/config.json")["downscale"], 2);

  // eval and render follow the run's factor, or the flag's.
  Outcome eval = runGlint("eval " + path("D2") + " --spp 1 --save-images");
  ASSERT_EQ(eval.status, 0) << eval.output;
  EXPECT_EQ(readJsonFile(path("D2") + "/eval/metrics.json")["width"], 32);
  // The report shows the ground truth at the evaluated size.
  Outcome report = runGlint("report " + path("D2"));
  EXPECT_EQ(report.status, 0) << report.output;
  Outcome eval4 = runGlint("eval " + path("D2") + " --spp 1 --downscale 4 -o " + path("m4.json"));
  ASSERT_EQ(eval4.status, 0) << eval4.output;
  EXPECT_EQ(readJsonFile(path("m4.json"))["width"], 16);
  EXPECT_EQ(readJsonFile(path("m4.json"))["height"], 12);
  Outcome render = runGlint("render " + path("D2") + " --downscale 5 -o " + path("r5"));
  ASSERT_EQ(render.status, 0) << render.output;
  const Image image = readImage(path("r5") + "/render/render_r_0.exr");
  EXPECT_EQ(image.width, 12);  // 64 / 5, the remainder dropped
  EXPECT_EQ(image.height, 9);

  Outcome tooMuch = runGlint("train " + path("N64") + " -o " + path("D99") + " --downscale 99");
  EXPECT_NE(tooMuch.status, 0);
  EXPECT_NE(tooMuch.output.find("--downscale"), std::string::npos) << tooMuch.output;
}

TEST_F(DatasetLayoutsCliTest, ADatasetHoldingOneSplitRendersAndEvaluatesIt) {
  Outcome synth = runGlint("synth builtin:spheres -o " + path("S") + " --train 2 --test 2 --res 16x12 --spp 2");
  ASSERT_EQ(synth.status, 0) << synth.output;
  fs::remove(path("S") + "/transforms_train.json");
  test::writeSmallCloud(path("cloud.ply"));
  Outcome render = runGlint("render " + path("cloud.ply") + " --dataset " + path("S") + " --split test -o " +
                            path("one"));
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_TRUE(fs::exists(path("one") + "/render/render_0001.exr"));
  Outcome eval = runGlint("eval " + path("cloud.ply") + " --dataset " + path("S") + " -o " + path("one.json") +
                          " --spp 1");
  EXPECT_EQ(eval.status, 0) << eval.output;
  Outcome train = runGlint("render " + path("cloud.ply") + " --dataset " + path("S") + " --split train -o " +
                           path("none"));
  EXPECT_NE(train.status, 0);
  EXPECT_NE(train.output.find("transforms_train.json: file not found: this dataset holds the test split only"),
            std::string::npos)
      << train.output;
}

TEST_F(DatasetLayoutsCliTest, AFailedStartLeavesNothingThatBlocksTheRetry) {
  // A broken image that only the full load reads (the first opens fine).
  fs::copy(path("N"), path("broken"), fs::copy_options::recursive);
  std::ofstream(path("broken") + "/train/r_2.png", std::ios::trunc) << "not a PNG";
  Outcome failed = runGlint("train " + path("broken") + " -o " + path("F") + " --iters 2");
  EXPECT_NE(failed.status, 0);
  EXPECT_NE(failed.output.find("r_2.png"), std::string::npos) << failed.output;
  EXPECT_FALSE(fs::exists(path("F"))) << "the failed start left its run folder";
  // Nor does a setting the config check refuses.
  std::ofstream(path("bad.json")) << "{\"f0_tint_from_reflections\": true}";
  Outcome badConfig = runGlint("train " + path("N") + " -o " + path("F") + " --iters 2 --config " + path("bad.json"));
  EXPECT_NE(badConfig.status, 0);
  EXPECT_NE(badConfig.output.find("bad.json"), std::string::npos) << badConfig.output;
  EXPECT_FALSE(fs::exists(path("F"))) << "the refused config left a run folder";

  // A folder the user made stays, with the user's files in it.
  fs::create_directories(path("mine"));
  Outcome intoEmpty = runGlint("train " + path("broken") + " -o " + path("mine") + " --iters 2");
  EXPECT_NE(intoEmpty.status, 0);
  EXPECT_TRUE(fs::is_directory(path("mine")));
  EXPECT_TRUE(fs::is_empty(path("mine")));

  // Repaired, the same command runs without --force.
  fs::copy_file(path("N") + "/train/r_2.png", path("broken") + "/train/r_2.png", fs::copy_options::overwrite_existing);
  Outcome retry = runGlint("train " + path("broken") + " -o " + path("F") + " --iters 2 --threads 2");
  EXPECT_EQ(retry.status, 0) << retry.output;

  // A start killed before its first checkpoint leaves config.json (and log.csv) only: that
  // does not block a new start either.
  fs::create_directories(path("killed"));
  fs::copy_file(path("F") + "/config.json", path("killed") + "/config.json");
  std::ofstream(path("killed") + "/log.csv") << "step,loss\n";
  Outcome afterKill = runGlint("train " + path("broken") + " -o " + path("killed") + " --iters 2 --threads 2");
  EXPECT_EQ(afterKill.status, 0) << afterKill.output;
  EXPECT_NE(afterKill.output.find("never saved a checkpoint; starting afresh"), std::string::npos) << afterKill.output;
  // But a run with a checkpoint still does.
  Outcome again = runGlint("train " + path("broken") + " -o " + path("killed") + " --iters 2");
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("continue it with --resume"), std::string::npos) << again.output;
}

}  // namespace
}  // namespace glint
