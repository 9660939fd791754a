// `glint train` and `glint eval` end to end: a run killed with SIGKILL and resumed writes
// the same scene.ply, byte for byte, as the uninterrupted run; bad input is refused; the
// log reaches TensorBoard.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "common/tfrecord_reader.h"
#include "eval/training_log.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

using test::readBytes;

class TrainCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("glint_train_cli_test_" + std::to_string(getpid())));
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    Outcome synth =
        runGlint("synth builtin:spheres -o " + (*root_ / "D").string() + " --train 8 --test 2 --res 32x24 --spp 4");
    ASSERT_EQ(synth.status, 0) << synth.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  static std::string path(const std::string& name) { return (*root_ / name).string(); }
  static fs::path* root_;
};

fs::path* TrainCliTest::root_ = nullptr;

const char* kTrainFlags = " --iters 600 --batch-rays 512 --save-every 100 --eval-every 200 --threads 2 --seed 3";

TEST_F(TrainCliTest, KilledAndResumedRunMatchesTheUninterruptedOne) {
  // The default schedule in 600 steps, after the kill at the first checkpoint (step 100):
  // reflections and the far-field Gaussians (fewer, for a 32x24 dataset) from step 300,
  // pruning from 400, a densification at 500 and 600.
  std::ofstream(path("small.json"))
      << R"({"far_field": {"count": 3000}, "reflection_warmup": 300, "prune": {"start": 400, "every": 50},)"
      << R"( "densify": {"start": 500, "every": 100}})";
  const std::string flags = std::string(kTrainFlags) + " --config " + path("small.json");
  Outcome straight = runGlint("train " + path("D") + " -o " + path("A") + flags);
  ASSERT_EQ(straight.status, 0) << straight.output;
  ASSERT_TRUE(fs::exists(path("A") + "/scene.ply"));
  for (const char* file : {"config.json", "log.csv", "checkpoint/state.bin"})
    EXPECT_TRUE(fs::exists(path("A") + "/" + file)) << file;

  // Start the same run in the background and SIGKILL it once its first checkpoint exists.
  std::string command = std::string(GLINT_BINARY) + " train " + path("D") + " -o " + path("B") + flags +
                        " > " + path("B.log") + " 2>&1 & echo $! > " + path("B.pid");
  ASSERT_EQ(std::system(command.c_str()), 0);
  fs::path checkpoint = path("B") + "/checkpoint/state.bin";
  auto start = std::chrono::steady_clock::now();
  while (!fs::exists(checkpoint) && std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  pid_t pid = std::stoi(readBytes(path("B.pid")));
  ASSERT_EQ(kill(pid, SIGKILL), 0) << "the run ended before it could be killed";
  while (kill(pid, 0) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::string log = readBytes(path("B") + "/log.csv");
  EXPECT_EQ(log.find("\n600,"), std::string::npos) << "the run was killed only after it finished";

  Outcome resumed = runGlint("train -o " + path("B") + " --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  EXPECT_EQ(readBytes(path("A") + "/scene.ply"), readBytes(path("B") + "/scene.ply"));
  // The log has each step once, as if never stopped.
  std::string resumedLog = readBytes(path("B") + "/log.csv");
  EXPECT_EQ(std::count(resumedLog.begin(), resumedLog.end(), '\n'), 601);
  // The resumed steps crossed the schedule's changes: the far field joined (the Gaussian
  // count rose at step 301; row i is step i + 1) and pruning removed Gaussians at step 400.
  const TrainingLog trained = readTrainingLog(path("B") + "/log.csv", {"gaussians"});
  const std::vector<double>& count = trained.column("gaussians");
  ASSERT_EQ(count.size(), 600u);
  EXPECT_GT(count[300], count[299]) << "no far field joined";
  EXPECT_LT(count[399], count[398]) << "no pruning at step 400";

  // The run evaluates and renders.
  Outcome eval = runGlint("eval " + path("A"));
  EXPECT_EQ(eval.status, 0) << eval.output;
  EXPECT_TRUE(fs::exists(path("A") + "/eval/metrics.json"));
  Outcome debug = runGlint("render " + path("A") + " --debug-pixel 16,20 --view 1 --bounces 2");
  EXPECT_EQ(debug.status, 0) << debug.output;
  EXPECT_NE(debug.output.find("sample 0 segment 0"), std::string::npos) << debug.output;
  EXPECT_NE(debug.output.find("hit 0: Gaussian"), std::string::npos) << debug.output;
  Outcome outside = runGlint("render " + path("A") + " --debug-pixel 32,0");
  EXPECT_NE(outside.status, 0);
  EXPECT_NE(outside.output.find("outside the 32x24 image"), std::string::npos) << outside.output;
}

// --baseline rgb fits the first segment's colour to the render buffer, with no G-buffer
// losses and no reflections, and says so in its config.
TEST_F(TrainCliTest, RgbBaselineTrainsOnTheRenderBufferAlone) {
  Outcome run = runGlint("train " + path("D") + " -o " + path("rgb") + " --baseline rgb --iters 20 --batch-rays 512");
  ASSERT_EQ(run.status, 0) << run.output;
  nlohmann::json config = nlohmann::json::parse(readBytes(path("rgb") + "/config.json"));
  EXPECT_EQ(config["baseline"], "rgb");
  EXPECT_EQ(config["bounces"], 0);
  for (const char* term : {"depth", "normal", "roughness", "f0", "specular"}) EXPECT_EQ(config["loss"][term], 0.0) << term;
  EXPECT_GT(config["loss"]["diffuse"].get<double>(), 0.0);
  std::string log = readBytes(path("rgb") + "/log.csv");
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 21);
  // The same steps, beside log.csv, for `tensorboard --logdir RUN`.
  std::vector<fs::path> events;
  for (const fs::directory_entry& e : fs::directory_iterator(path("rgb")))
    if (e.path().filename().string().rfind("events.out.tfevents.", 0) == 0) events.push_back(e.path());
  ASSERT_EQ(events.size(), 1u);
  const test::EventFile board = test::readEventFile(events[0].string());
  EXPECT_TRUE(board.framingValid);
  EXPECT_EQ(board.fileVersion, "brain.Event:2");
  int losses = 0, scores = 0;
  for (const test::ScalarEvent& e : board.scalars) {
    losses += e.tag == "loss";
    scores += e.tag == "test/diffuse_psnr";
  }
  EXPECT_EQ(losses, 20);
  EXPECT_EQ(scores, 1);  // the last step is scored

  Outcome mixed = runGlint("train " + path("D") + " -o " + path("rgb2") + " --baseline rgb --bounces 2 --iters 5");
  EXPECT_NE(mixed.status, 0);
  EXPECT_NE(mixed.output.find("--bounces"), std::string::npos) << mixed.output;
}

TEST_F(TrainCliTest, RefusesBadInput) {
  Outcome noDataset = runGlint("train " + path("missing") + " -o " + path("X") + " --iters 5");
  EXPECT_NE(noDataset.status, 0);
  EXPECT_NE(noDataset.output.find("missing"), std::string::npos) << noDataset.output;

  fs::create_directories(path("busy"));
  std::ofstream(path("busy") + "/mine.txt") << "keep me";
  Outcome busy = runGlint("train " + path("D") + " -o " + path("busy") + " --iters 5");
  EXPECT_NE(busy.status, 0);
  EXPECT_NE(busy.output.find("not empty"), std::string::npos) << busy.output;
  EXPECT_EQ(readBytes(path("busy") + "/mine.txt"), "keep me");

  std::ofstream(path("bad.json")) << "{\"batch_rays\": -4}";
  Outcome badConfig = runGlint("train " + path("D") + " -o " + path("Y") + " --config " + path("bad.json"));
  EXPECT_NE(badConfig.status, 0);
  EXPECT_NE(badConfig.output.find("bad.json"), std::string::npos) << badConfig.output;

  Outcome noRun = runGlint("train -o " + path("nothing") + " --resume");
  EXPECT_NE(noRun.status, 0);
  EXPECT_NE(noRun.output.find("config.json"), std::string::npos) << noRun.output;
}

// --batch-images trains on whole views (said in the log, kept in config.json), warns when a
// pruning interval sees fewer views than the run has, and refuses the random-pixel flags.
TEST_F(TrainCliTest, WholeImageBatchesAreSaidKeptAndExclusive) {
  Outcome run = runGlint("train " + path("D") + " -o " + path("whole") + " --batch-images 2 --iters 3 --threads 2");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("every pixel of 2 views per step"), std::string::npos) << run.output;
  EXPECT_EQ(nlohmann::json::parse(readBytes(path("whole") + "/config.json"))["batch_images"], 2);
  EXPECT_EQ(run.output.find("pruning interval"), std::string::npos) << run.output;

  std::ofstream(path("short_prune.json")) << "{\"batch_images\": 1, \"prune\": {\"every\": 3, \"start\": 0}}";
  Outcome shortInterval = runGlint("train " + path("D") + " -o " + path("short") + " --config " +
                                   path("short_prune.json") + " --iters 2 --threads 2");
  ASSERT_EQ(shortInterval.status, 0) << shortInterval.output;
  EXPECT_NE(shortInterval.output.find("pruning interval"), std::string::npos) << shortInterval.output;

  Outcome both = runGlint("train " + path("D") + " -o " + path("both") + " --batch-images 1 --batch-rays 512");
  EXPECT_NE(both.status, 0);
  EXPECT_NE(both.output.find("--batch-rays"), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(path("both")));
  Outcome configAndFlag = runGlint("train " + path("D") + " -o " + path("both2") + " --config " +
                                   path("short_prune.json") + " --batch-views 2");
  EXPECT_NE(configAndFlag.status, 0);
  EXPECT_NE(configAndFlag.output.find("short_prune.json"), std::string::npos) << configAndFlag.output;
}

TEST_F(TrainCliTest, DivergenceStopsWithAMessageAndWritesNoCheckpointOfTheBrokenScene) {
  // Every learning rate at the largest value allowed: the Gaussians blow up within steps.
  std::ofstream(path("wild.json"))
      << R"({"lr": {"position_init": 9.99, "position_final": 9.99, "rotation": 9.99, "scale": 9.99, "opacity": 9.99,
                    "diffuse": 9.99, "normal": 9.99, "normal_final": 9.99, "roughness": 9.99, "f0": 9.99}})";
  Outcome run = runGlint("train " + path("D") + " -o " + path("wild") + " --config " + path("wild.json") +
                         " --iters 2000 --batch-rays 512 --save-every 50 --threads 2");
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("training diverged"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("learning rates"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("glint train: done"), std::string::npos) << run.output;
  // The scales explode in the first step, before any checkpoint: none is written, and the
  // message says so rather than naming a checkpoint of the broken scene.
  EXPECT_NE(run.output.find("training diverged at step 1: the scales have exploded"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("no checkpoint was written"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("wild") + "/checkpoint/state.bin"));
}

TEST_F(TrainCliTest, ARunWithoutCheckpointResumesFromTheStartAndTheAdviceSaysSo) {
  // A dataset whose second render image is broken: info refuses it, and so must train.
  // The failed start takes back the folder it made (dataset_layouts_cli_test has more).
  fs::copy(path("D"), path("D_broken"), fs::copy_options::recursive);
  std::ofstream(path("D_broken") + "/train/render/render_0001.exr", std::ios::trunc) << "not an EXR";
  Outcome failed = runGlint("train " + path("D_broken") + " -o " + path("early") + " --iters 5 --batch-rays 256");
  EXPECT_NE(failed.status, 0);
  EXPECT_NE(failed.output.find("render_0001.exr"), std::string::npos) << failed.output;
  EXPECT_FALSE(fs::exists(path("early")));

  // A start killed before its first checkpoint leaves its config.json: --resume starts it
  // from step 0 with that config, as the advice says.
  Outcome configOnly = runGlint("train " + path("D") + " -o " + path("configured") + " --iters 5 --batch-rays 256");
  ASSERT_EQ(configOnly.status, 0) << configOnly.output;
  fs::create_directories(path("early"));
  fs::copy_file(path("configured") + "/config.json", path("early") + "/config.json");
  Outcome resumed = runGlint("train -o " + path("early") + " --resume");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("has no checkpoint yet; starting it from step 0"), std::string::npos)
      << resumed.output;
  EXPECT_TRUE(fs::exists(path("early") + "/scene.ply"));
}

TEST_F(TrainCliTest, ADamagedLogOnResumeIsAnErrorNamingItsLine) {
  Outcome first = runGlint("train " + path("D") + " -o " + path("logged") + " --iters 6 --save-every 3 --batch-rays 256");
  ASSERT_EQ(first.status, 0) << first.output;
  std::string log = readBytes(path("logged") + "/log.csv");
  size_t third = log.find('\n', log.find('\n') + 1) + 1;  // start of line 3 (step 2)
  log.replace(third, log.find('\n', third) - third, "2,garbage");
  std::ofstream(path("logged") + "/log.csv", std::ios::trunc) << log;
  Outcome resumed = runGlint("train -o " + path("logged") + " --resume --iters 8");
  EXPECT_NE(resumed.status, 0);
  EXPECT_NE(resumed.output.find("log.csv: line 3"), std::string::npos) << resumed.output;
  EXPECT_EQ(resumed.output.find("stoll"), std::string::npos) << resumed.output;

  // A last row cut short (no newline: a crash mid-write) is dropped, not an error.
  Outcome second = runGlint("train " + path("D") + " -o " + path("cut") + " --iters 6 --save-every 3 --batch-rays 256");
  ASSERT_EQ(second.status, 0) << second.output;
  std::ofstream(path("cut") + "/log.csv", std::ios::app) << "7,0.5,0.1";
  Outcome cutResumed = runGlint("train -o " + path("cut") + " --resume --iters 8");
  EXPECT_EQ(cutResumed.status, 0) << cutResumed.output;
}

}  // namespace
}  // namespace glint
