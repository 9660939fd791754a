// `glint render --path` (camera-path frames and the MP4) and `--progressive`, run as a user would.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/run_glint.h"
#include "app/small_cloud.h"
#include "io/image.h"

namespace {

namespace fs = std::filesystem;

using glint::test::Outcome;
using glint::test::runGlint;

class RenderPathCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("glint_render_path_test_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 2 --test 4 --res 20x15 --spp 1");
    ASSERT_EQ(synth.status, 0) << synth.output;
    glint::test::writeSmallCloud(root_ / "cloud.ply");
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  std::string render(const std::string& out, const std::string& flags) const {
    return "render " + path("cloud.ply") + " --dataset " + path("D") + " -o " + path(out) + " " + flags;
  }
  fs::path root_;
};

std::string frameName(int f) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", f);
  return name;
}

TEST_F(RenderPathCliTest, OrbitWritesMovingFramesDenoisedFramesAndAnMp4) {
  Outcome run = runGlint(render("P", "--path orbit --frames 6 --spp 2 --denoise --fps 12"));
  ASSERT_EQ(run.status, 0) << run.output;
  for (int f = 0; f < 6; ++f) {
    EXPECT_TRUE(fs::exists(root_ / "P" / "path" / frameName(f))) << f;
    EXPECT_TRUE(fs::exists(root_ / "P" / "path_denoised" / frameName(f))) << f;
  }
  EXPECT_FALSE(fs::exists(root_ / "P" / "path" / frameName(6)));
  glint::Image first = glint::readImage(root_ / "P" / "path" / frameName(0));
  glint::Image half = glint::readImage(root_ / "P" / "path" / frameName(3));
  EXPECT_EQ(first.width, 20);
  EXPECT_EQ(first.height, 15);
  EXPECT_NE(first.pixels, half.pixels);  // the camera moved round the cloud

  fs::path video = root_ / "P" / "path.mp4";
  if (run.output.find("ffmpeg is not installed") != std::string::npos) {
    EXPECT_FALSE(fs::exists(video));
  } else {
    ASSERT_TRUE(fs::exists(video)) << run.output;
    std::ifstream in(video, std::ios::binary);
    char header[8] = {};
    in.read(header, 8);
    EXPECT_EQ(std::string(header + 4, 4), "ftyp");  // an ISO media file
    EXPECT_NE(run.output.find("6 frames at 12 fps"), std::string::npos) << run.output;
  }
  // No temporary files are left behind.
  for (const auto& entry : fs::directory_iterator(root_ / "P"))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(RenderPathCliTest, DatasetTestFramesAreTheTestViewsRenders) {
  Outcome frames = runGlint(render("P", "--path dataset-test --spp 3 --no-video"));
  ASSERT_EQ(frames.status, 0) << frames.output;
  EXPECT_FALSE(fs::exists(root_ / "P" / "path.mp4"));
  Outcome views = runGlint(render("R", "--spp 3 --format png"));
  ASSERT_EQ(views.status, 0) << views.output;
  for (int v = 0; v < 4; ++v) {
    char view[64];
    std::snprintf(view, sizeof view, "render/render_%04d.png", v);
    glint::Image a = glint::readImage(root_ / "P" / "path" / frameName(v));
    glint::Image b = glint::readImage(root_ / "R" / view);
    EXPECT_EQ(a.pixels, b.pixels) << v;
  }
  EXPECT_FALSE(fs::exists(root_ / "P" / "path" / frameName(4)));
  // More frames than views interpolate between them.
  Outcome dense = runGlint(render("P2", "--path dataset-test --frames 7 --spp 1 --no-video"));
  ASSERT_EQ(dense.status, 0) << dense.output;
  EXPECT_TRUE(fs::exists(root_ / "P2" / "path" / frameName(6)));
}

TEST_F(RenderPathCliTest, ProgressiveRenderEndsAtTheOnePassRender) {
  Outcome progressive = runGlint(render("A", "--spp 5 --progressive --bounces 2"));
  ASSERT_EQ(progressive.status, 0) << progressive.output;
  EXPECT_NE(progressive.output.find("progressive"), std::string::npos) << progressive.output;
  Outcome once = runGlint(render("B", "--spp 5 --bounces 2"));
  ASSERT_EQ(once.status, 0) << once.output;
  for (const char* buffer : {"render", "diffuse", "specular", "depth"})
    for (int v = 0; v < 4; ++v) {
      char name[64];
      std::snprintf(name, sizeof name, "%s/%s_%04d.exr", buffer, buffer, v);
      glint::Image a = glint::readImage(root_ / "A" / name), b = glint::readImage(root_ / "B" / name);
      ASSERT_EQ(a.pixels.size(), b.pixels.size());
      for (size_t i = 0; i < a.pixels.size(); ++i)
        ASSERT_NEAR(a.pixels[i], b.pixels[i], 1e-5f * (1 + std::abs(b.pixels[i]))) << name << " " << i;
    }
}

TEST_F(RenderPathCliTest, BadPathFlagsGetOneClearErrorAndNothingIsOverwritten) {
  struct Case {
    std::string flags, mentions;
  };
  for (const Case& c : {Case{"--path helix", "--path"}, Case{"--path orbit --frames 0", "--frames"},
                        Case{"--path orbit --fps 1000", "--fps"},
                        Case{"--path orbit --debug-pixel 1,1", "--debug-pixel"}}) {
    Outcome run = runGlint(render("X", c.flags));
    EXPECT_NE(run.status, 0) << c.flags;
    EXPECT_NE(run.output.find(c.mentions), std::string::npos) << c.flags << ": " << run.output;
  }
  // A folder holding a view render is not a path render's: refused without --force.
  ASSERT_EQ(runGlint(render("R", "--spp 1")).status, 0);
  Outcome into = runGlint(render("R", "--path orbit --frames 2 --no-video"));
  EXPECT_NE(into.status, 0);
  EXPECT_NE(into.output.find("not empty"), std::string::npos) << into.output;
  EXPECT_FALSE(fs::exists(root_ / "R" / "path"));
}

}  // namespace
