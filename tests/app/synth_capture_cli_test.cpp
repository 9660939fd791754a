// `glint synth --layout capture`: a capture folder that `glint info` opens clean, guarded
// against overwriting and against mixing it with the transforms layout.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "app/run_glint.h"

namespace {

namespace fs = std::filesystem;
using glint::test::Outcome;
using glint::test::runGlint;

class SynthCaptureCli : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_synth_capture_cli_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

const std::string kTiny = " --layout capture --train 9 --res 32x24 --spp 2 --bounces 2 --points 200";

TEST_F(SynthCaptureCli, NetworkLikeCaptureOpensCleanWithHeldOutViews) {
  Outcome synth = runGlint("synth builtin:gallery -o " + path("C") + kTiny + " --degrade network");
  ASSERT_EQ(synth.status, 0) << synth.output;
  EXPECT_NE(synth.output.find("9 views, 2 held out"), std::string::npos) << synth.output;
  EXPECT_NE(synth.output.find("network-like priors"), std::string::npos) << synth.output;
  EXPECT_TRUE(fs::exists(root_ / "C" / "images" / "view_0008.jpg"));
  Outcome info = runGlint("info " + path("C"));
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("train: 7 views"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("test: 2 views"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("problems: none"), std::string::npos) << info.output;

  // A second run needs --force; the other layout is refused even with it.
  Outcome again = runGlint("synth builtin:gallery -o " + path("C") + kTiny);
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
  Outcome forced = runGlint("synth builtin:gallery -o " + path("C") + kTiny + " --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  Outcome mixed = runGlint("synth builtin:spheres -o " + path("C") + " --train 1 --test 1 --res 8x8 --spp 1 --force");
  EXPECT_NE(mixed.status, 0);
  EXPECT_NE(mixed.output.find("capture layout"), std::string::npos) << mixed.output;
  EXPECT_FALSE(fs::exists(root_ / "C" / "transforms_train.json"));
}

TEST_F(SynthCaptureCli, DegradingNeedsTheCaptureLayout) {
  Outcome run = runGlint("synth builtin:gallery -o " + path("T") + " --train 1 --test 1 --res 8x8 --spp 1 "
                         "--degrade network");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("--layout capture"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(root_ / "T"));
}

// --degrade-only names which priors the degradation reaches, so it means nothing alone, and
// it is said on the progress line.
TEST_F(SynthCaptureCli, DegradeOnlyNeedsADegradationAndIsReported) {
  Outcome alone = runGlint("synth builtin:gallery -o " + path("A") + kTiny + " --degrade-only normal");
  EXPECT_NE(alone.status, 0);
  EXPECT_NE(alone.output.find("--degrade network or monocular"), std::string::npos) << alone.output;
  EXPECT_FALSE(fs::exists(root_ / "A"));
  Outcome unknown = runGlint("synth builtin:gallery -o " + path("U") + kTiny + " --degrade network --degrade-only albedo");
  EXPECT_NE(unknown.status, 0);
  EXPECT_FALSE(fs::exists(root_ / "U"));
  Outcome two = runGlint("synth builtin:gallery -o " + path("N") + kTiny + " --degrade network --degrade-only normal,roughness");
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_NE(two.output.find("network-like (only normal, roughness) priors"), std::string::npos) << two.output;
}

}  // namespace
