// Every command that opens a training run reads RUN/config.json through one reader
// (train/run_folder.h), so a setting out of its range is refused by each of them with the
// very same message, naming the file and the key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

#include "app/run_glint.h"
#include "app/small_cloud.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

struct BadSetting {
  const char* name;     // of the test case
  const char* config;   // the whole of RUN/config.json
  const char* problem;  // what the message says after the file name
};

// Test names show the case's name, not its bytes.
void PrintTo(const BadSetting& setting, std::ostream* os) { *os << setting.name; }

class RunConfigCliTest : public ::testing::TestWithParam<BadSetting> {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_run_config_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "run");
    test::writeSmallCloud(root_ / "run" / "scene.ply");
    std::ofstream(root_ / "run" / "config.json") << GetParam().config;
    std::ofstream(root_ / "edits.json") << R"({"glint_edits": 1, "selections": {}, "operations": []})";
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

TEST_P(RunConfigCliTest, EveryCommandRefusesItWithTheSameMessage) {
  const std::string expected =
      "glint: error: " + path("run/config.json") + ": " + GetParam().problem + "\n";
  const std::string run = path("run");
  for (const std::string& command :
       {"train -o " + run + " --resume", "render " + run + " -o " + path("R"), "eval " + run,
        "view " + run + " --port 0", "report " + run, "edit " + run + " " + path("edits.json") + " -o " +
        path("edited.ply")}) {
    Outcome outcome = runGlint(command);
    EXPECT_EQ(outcome.status, 1) << command << "\n" << outcome.output;
    EXPECT_EQ(outcome.output, expected) << command;
  }
}

INSTANTIATE_TEST_SUITE_P(
    OutOfRange, RunConfigCliTest,
    ::testing::Values(
        BadSetting{"KernelPower", R"({"trace": {"kernel_power": 100}})", "trace.kernel_power must be in [0.25, 16]"},
        BadSetting{"InvalidNormalLength", R"({"invalid_normal_length": -1})",
                   "invalid_normal_length must be in [0, 1]"},
        BadSetting{"BackfaceSkip", R"({"backface_skip": -0.5})", "backface_skip must be non-negative"},
        BadSetting{"Bounces", R"({"bounces": 9})", "bounces must be in [0, 8]"},
        BadSetting{"CullRegion", R"({"prune": {"camera_cull_region": "everywhere"}})",
                   R"("prune.camera_cull_region" is "everywhere"; expected "in-view" or "whole-sphere")"}),
    [](const ::testing::TestParamInfo<BadSetting>& info) { return std::string(info.param.name); });

// A flag over the run's settings is checked by the same rule as config.json.
TEST(RunConfigFlags, AreCheckedByTheSameRule) {
  test::TempFolder folder;
  fs::create_directories(folder.path() / "run");
  test::writeSmallCloud(folder.path() / "run" / "scene.ply");
  std::ofstream(folder.path() / "run" / "config.json") << "{}";
  for (const char* command : {"render", "eval"}) {
    Outcome outcome = runGlint(std::string(command) + " " + (folder.path() / "run").string() +
                               " --kernel-power 100 -o " + (folder.path() / "out").string());
    EXPECT_EQ(outcome.status, 1) << outcome.output;
    EXPECT_EQ(outcome.output, "glint: error: command line: trace.kernel_power must be in [0.25, 16]\n") << command;
  }
}

}  // namespace
}  // namespace glint
