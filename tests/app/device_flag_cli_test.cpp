// --device on the commands that trace (render, eval, view, export --bake-reflections, train), run as a
// user would: auto says which device it took; cuda without a GPU (or in a build without
// CUDA) is one clear error, never a silent CPU render; contradicting flags are refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "app/run_glint.h"
#include "app/small_cloud.h"
#include "tracers/compute_device.h"

namespace {

namespace fs = std::filesystem;

using glint::test::Outcome;
using glint::test::runGlint;

class DeviceFlagCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_device_flag_test_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 2 --test 2 --res 20x15 --spp 1");
    ASSERT_EQ(synth.status, 0) << synth.output;
    glint::test::writeSmallCloud(root_ / "cloud.ply");
    std::string why;
    gpu_ = glint::findGpu(&why).has_value();
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  std::string render(const std::string& out, const std::string& flags) const {
    return "render " + path("cloud.ply") + " --dataset " + path("D") + " -o " + path(out) + " --spp 1 " + flags;
  }
  fs::path root_;
  bool gpu_ = false;
};

TEST_F(DeviceFlagCliTest, AutoSaysWhichDeviceItTook) {
  Outcome run = runGlint(render("auto", ""));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(gpu_ ? "device: GPU" : "device: CPU (no GPU: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(gpu_ ? "cuda tracer" : "fast tracer"), std::string::npos) << run.output;
}

TEST_F(DeviceFlagCliTest, CpuIsTheFastTracer) {
  Outcome run = runGlint(render("cpu", "--device cpu"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("device: CPU (--device cpu)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("fast tracer"), std::string::npos) << run.output;
}

TEST_F(DeviceFlagCliTest, CudaWithoutAGpuIsOneClearError) {
  Outcome run = runGlint(render("cuda", "--device cuda"));
  if (gpu_) {
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("cuda tracer"), std::string::npos) << run.output;
    return;
  }
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("--device cuda: no GPU to use: "), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(root_ / "cuda" / "render")) << "nothing rendered on the CPU instead";
  // The same for eval and the viewer, before any work.
  Outcome eval = runGlint("eval " + path("cloud.ply") + " --dataset " + path("D") + " -o " + path("m.json") +
                          " --spp 1 --device cuda");
  EXPECT_NE(eval.status, 0);
  EXPECT_NE(eval.output.find("--device cuda: no GPU to use: "), std::string::npos) << eval.output;
  Outcome view = runGlint("view " + path("cloud.ply") + " --device cuda", 20);
  EXPECT_NE(view.status, 0);
  EXPECT_NE(view.output.find("--device cuda: no GPU to use: "), std::string::npos) << view.output;
}

// Training traces on the CPU unless told otherwise; --device cuda takes the GPU (its
// wavefronts; issue 42's first part) or, without one, fails before a run folder is left.
TEST_F(DeviceFlagCliTest, TrainingTracesOnTheCpuByDefaultAndOnTheGpuWhenAsked) {
  Outcome cpu = runGlint("train " + path("D") + " -o " + path("run_cpu") + " --iters 2 --threads 2 --eval-views 0");
  ASSERT_EQ(cpu.status, 0) << cpu.output;
  EXPECT_NE(cpu.output.find("glint train: device: CPU (--device cpu)"), std::string::npos) << cpu.output;
  Outcome cuda = runGlint("train " + path("D") + " -o " + path("run_cuda") + " --iters 2 --threads 2 --device cuda");
  if (gpu_) {
    ASSERT_EQ(cuda.status, 0) << cuda.output;
    EXPECT_NE(cuda.output.find("cuda tracer"), std::string::npos) << cuda.output;
    // The GPU run's checkpoint goes on on the CPU.
    Outcome resumed = runGlint("train -o " + path("run_cuda") + " --resume --iters 4 --threads 2 --device cpu");
    EXPECT_EQ(resumed.status, 0) << resumed.output;
    return;
  }
  EXPECT_NE(cuda.status, 0);
  EXPECT_NE(cuda.output.find("--device cuda: no GPU to use: "), std::string::npos) << cuda.output;
  EXPECT_FALSE(fs::exists(root_ / "run_cuda")) << "a start that failed leaves no run folder";
}

TEST_F(DeviceFlagCliTest, ContradictingTracerAndDeviceAreRefused) {
  Outcome run = runGlint(render("both", "--device cuda --tracer fast"));
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("--tracer fast and --device cuda disagree"), std::string::npos) << run.output;
  Outcome unknown = runGlint(render("bad", "--device tpu"));
  EXPECT_NE(unknown.status, 0);
  EXPECT_NE(unknown.output.find("--device"), std::string::npos) << unknown.output;
}

TEST_F(DeviceFlagCliTest, VersionSaysWhetherCudaIsBuiltIn) {
  Outcome run = runGlint("--version");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(glint::builtWithCuda() ? "(with CUDA " : "(without CUDA)"), std::string::npos)
      << run.output;
}

}  // namespace
