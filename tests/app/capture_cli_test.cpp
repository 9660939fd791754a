// A real capture through the commands: info, train (with a buffer kind missing), eval and
// render of views of different sizes and off-centre principal points; bad captures are
// refused with the file named.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "common/floor_capture.h"
#include "io/image.h"
#include "io/json_file.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

class CaptureCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_capture_cli_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    test::writeFloorCapture(root_ / "C");
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(CaptureCliTest, TrainsEvaluatesAndRendersACapture) {
  fs::remove_all(root_ / "C" / "priors" / "specular");
  Outcome info = runGlint("info " + (root_ / "C").string() + " --holdout 4");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("COLMAP text model sparse/0, 10 images, 400 points"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("depth aligned to the sparse points in 10 of 10 views"), std::string::npos)
      << info.output;

  const std::string run = (root_ / "RUN").string();
  Outcome train = runGlint("train " + (root_ / "C").string() + " -o " + run +
                           " --holdout 4 --iters 40 --bounces 1 --eval-every 20 --batch-rays 1024 --threads 2");
  ASSERT_EQ(train.status, 0) << train.output;
  EXPECT_NE(train.output.find("the dataset has no specular buffers"), std::string::npos) << train.output;
  EXPECT_EQ(readJsonFile(fs::path(run) / "config.json")["holdout"], 4);

  Outcome eval = runGlint("eval " + run + " --spp 1 --bounces 1");
  ASSERT_EQ(eval.status, 0) << eval.output;
  nlohmann::json metrics = readJsonFile(fs::path(run) / "eval" / "metrics.json");
  EXPECT_EQ(metrics["views"], 3);  // view_0000, view_0004, view_0008
  EXPECT_TRUE(metrics["mean"]["specular"]["psnr"].is_null()) << metrics["mean"].dump();
  EXPECT_TRUE(metrics["mean"]["final"]["psnr"].is_number()) << metrics["mean"].dump();

  // Each view renders at its own size: view 9 (a training view) is 40x30, the others 48x36.
  const fs::path out = root_ / "R";
  Outcome render = runGlint("render " + run + " --split train --spp 1 -o " + out.string());
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_EQ(readImage(out / "render" / "render_view_0009.exr").width, 40);
  EXPECT_EQ(readImage(out / "render" / "render_view_0001.exr").width, 48);
}

// A capture's buffers are predicted unless capture.json says "priors": "exact": predicted
// ones train with the real-capture setting, said in one line, unless --config is given.
TEST_F(CaptureCliTest, PredictedBuffersTrainWithTheRealCaptureSetting) {
  const fs::path capture = root_ / "C";
  nlohmann::json decoding = readJsonFile(capture / "capture.json");
  EXPECT_EQ(decoding["priors"], "exact");  // writeCapture's buffers are rendered
  const std::string flags = " --holdout 4 --iters 2 --batch-rays 256 --eval-views 0 --threads 1";
  auto trainedConfig = [&](const std::string& name, const std::string& extra, Outcome* outcome) {
    *outcome = runGlint("train " + capture.string() + " -o " + (root_ / name).string() + flags + extra);
    EXPECT_EQ(outcome->status, 0) << outcome->output;
    return readJsonFile(root_ / name / "config.json");
  };
  Outcome outcome;
  nlohmann::json config = trainedConfig("EXACT", "", &outcome);
  EXPECT_EQ(config["loss"]["depth"], 2.5);
  EXPECT_EQ(config["roughness_shift_invariant"], false);
  EXPECT_EQ(outcome.output.find("predicted buffers"), std::string::npos) << outcome.output;

  decoding.erase("priors");  // a predictor's capture does not say so: predicted is the default
  std::ofstream(capture / "capture.json") << decoding.dump();
  config = trainedConfig("PREDICTED", " --bounces 1", &outcome);
  EXPECT_EQ(config["loss"]["depth"], 0.0);
  EXPECT_FLOAT_EQ(config["loss"]["specular"].get<float>(), 0.01f);
  EXPECT_EQ(config["bounces"], 1);  // a flag given still wins
  EXPECT_NE(outcome.output.find("holds predicted buffers"), std::string::npos) << outcome.output;

  std::ofstream(root_ / "mine.json") << R"({"loss": {"depth": 1.5}})";
  config = trainedConfig("CONFIGURED", " --config " + (root_ / "mine.json").string(), &outcome);
  EXPECT_EQ(config["loss"]["depth"], 1.5);
  EXPECT_EQ(config["loss"]["specular"], 3.0);
  EXPECT_EQ(outcome.output.find("predicted buffers"), std::string::npos) << outcome.output;
}

TEST_F(CaptureCliTest, BrokenCapturesAreRefusedNamingTheFile) {
  fs::remove(root_ / "C" / "images" / "view_0002.png");
  Outcome info = runGlint("info " + (root_ / "C").string());
  EXPECT_EQ(info.status, 2) << info.output;
  EXPECT_NE(info.output.find("view_0002.png"), std::string::npos) << info.output;
  Outcome train = runGlint("train " + (root_ / "C").string() + " -o " + (root_ / "RUN").string() + " --iters 5");
  EXPECT_NE(train.status, 0);
  EXPECT_NE(train.output.find("view_0002.png"), std::string::npos) << train.output;
  EXPECT_FALSE(fs::exists(root_ / "RUN" / "scene.ply"));
}

}  // namespace
}  // namespace glint
