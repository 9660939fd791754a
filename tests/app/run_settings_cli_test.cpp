// A run trained with settings other than the defaults (invalid_normal_length, backface_skip,
// kernel power) renders through `glint render RUN` bit for bit as training's own evaluation
// code renders it with the run's render path (train/training_eval.h, render_bounces): the
// command takes every trace and path setting from the run's config.json. Flags still
// override them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <optional>
#include <vector>

#include "app/rendered_buffers.h"
#include "app/run_glint.h"
#include "common/tiny_run.h"
#include "io/image.h"
#include "train/run_folder.h"
#include "train/training_loop.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

// Renders the test views with the trainer's tracer once the last step is done, as the
// loop's evaluation renders them, with the run's render path.
class FinalEvaluation : public TrainingObserver {
 public:
  FinalEvaluation(const TrainConfig& config, const TestViews& views) : config_(config), views_(views) {}
  void betweenSteps(const Trainer& trainer, const StepReport& report) override {
    if (report.step != config_.iters) return;
    for (size_t k = 0; k < views_.size(); ++k) rendered.push_back(views_.render(trainer.tracer(), k, 1, config_.renderPath()));
  }
  std::vector<ViewBuffers> rendered;

 private:
  const TrainConfig& config_;
  const TestViews& views_;
};

class RunSettingsCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_run_settings_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(RunSettingsCliTest, RenderOfARunIsBitForBitTheTrainersEvaluation) {
  test::makeTinyDataset(root_ / "D");
  TrainConfig config = test::tinyTrainConfig(root_ / "D", 6);
  // The defaults are 0.7, 0.1 and 3. Six steps leave the blended normals short (about 0.01),
  // so with the default threshold no path would reflect at all.
  config.invalidNormalLength = 0.005f;
  config.backfaceSkip = 0.3f;
  config.trace.kernelPower = 2.0f;
  const RunFolder run(root_ / "run");
  run.create(config, false);

  Dataset dataset = Dataset::open(config.dataset);
  TrainingSession session;
  session.evalViews = 2;
  TestViews views = TestViews::load(dataset, dataset.test(), session.evalViews);
  ASSERT_EQ(views.size(), dataset.test().views.size());  // view k of the score is view k of the split
  FinalEvaluation evaluation(config, views);
  TrainingOutcome outcome = trainRun(run, config, session, evaluation);
  ASSERT_FALSE(outcome.stopped);
  ASSERT_EQ(evaluation.rendered.size(), views.size());

  // No flag names a setting: every one comes from RUN/config.json.
  const fs::path out = root_ / "R";
  Outcome render = runGlint("render " + run.root().string() + " --split test --no-jitter -o " + out.string());
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_NE(render.output.find("p = 2,"), std::string::npos) << render.output;
  EXPECT_NE(render.output.find("4 bounces"), std::string::npos) << render.output;  // render_bounces
  bool anySpecular = false;
  for (size_t v = 0; v < views.size(); ++v) {
    for (Buffer b : kRenderedBuffers) {
      Image ours = readImage(renderedBufferPath(out, dataset.test().views[v].filePath, b));
      const Image& trainers = evaluation.rendered[v][b];
      ASSERT_EQ(ours.width, trainers.width);
      ASSERT_EQ(ours.height, trainers.height);
      EXPECT_EQ(ours.pixels, trainers.pixels) << "view " << v << " buffer " << int(b);
      if (b == Buffer::Specular)
        for (float x : ours.pixels) anySpecular = anySpecular || x != 0;
    }
  }
  EXPECT_TRUE(anySpecular) << "no reflected light: the path settings were not exercised";

  // The defaults instead of the run's settings (as before the run's were read) give
  // another image: the comparison above sees the difference.
  const fs::path defaults = root_ / "R_defaults";
  Outcome other = runGlint("render " + run.root().string() + " --split test --no-jitter --bounces 1 "
                           "--invalid-normal 0.7 --backface-skip 0.1 --kernel-power 3 -o " + defaults.string());
  ASSERT_EQ(other.status, 0) << other.output;
  Image changed = readImage(renderedBufferPath(defaults, dataset.test().views[0].filePath, Buffer::Render));
  EXPECT_NE(changed.pixels, evaluation.rendered[0][Buffer::Render].pixels);
}

}  // namespace
}  // namespace glint
