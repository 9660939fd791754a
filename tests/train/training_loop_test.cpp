// The training loop of a run folder: a run stopped by its observer saves a checkpoint, and
// resumed it ends bit for bit where the uninterrupted run ends; the observer hears every
// step, with a score on the eval_every steps.
#include "train/training_loop.h"

#include <gtest/gtest.h>

#include "common/expect_error.h"
#include "core/atomic_file.h"
#include "common/tiny_run.h"
#include "io/temp_folder.h"
#include "train/checkpoint.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// Counts what the loop reports and asks it to stop after `stopAfter` steps (0: never).
class CountingObserver : public TrainingObserver {
 public:
  explicit CountingObserver(int64_t stopAfter = 0) : stopAfter_(stopAfter) {}
  void started(const Trainer& trainer, const Dataset&, const TrainingViews&) override {
    ++starts;
    firstStep = trainer.stepCount();
  }
  void stepped(const StepReport& report, const std::optional<TestScore>& score) override {
    lastStep = report.step;
    if (score) ++scores;
  }
  bool stopRequested() override { return stopAfter_ > 0 && lastStep >= stopAfter_; }

  int starts = 0, scores = 0;
  int64_t firstStep = -1, lastStep = 0;

 private:
  int64_t stopAfter_;
};

class TrainingLoopTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new test::TempFolder();
    test::makeTinyDataset(folder_->path() / "D");
  }
  static void TearDownTestSuite() { delete folder_; }
  static TrainConfig smallConfig() { return test::tinyTrainConfig(folder_->path() / "D", 8); }

  static test::TempFolder* folder_;
};

test::TempFolder* TrainingLoopTest::folder_ = nullptr;

TEST_F(TrainingLoopTest, AStoppedRunResumesBitForBit) {
  const TrainConfig config = smallConfig();
  TrainingSession session;
  session.evalViews = 2;

  const RunFolder straight(folder_->path() / "straight");
  straight.create(config, false);
  CountingObserver all;
  TrainingOutcome done = trainRun(straight, config, session, all);
  EXPECT_FALSE(done.stopped);
  EXPECT_EQ(done.step, config.iters);
  EXPECT_EQ(all.starts, 1);
  EXPECT_EQ(all.scores, 2);  // steps 4 and 8
  EXPECT_EQ(all.lastStep, config.iters);

  const RunFolder stopped(folder_->path() / "stopped");
  stopped.create(config, false);
  CountingObserver early(5);
  TrainingOutcome partial = trainRun(stopped, config, session, early);
  EXPECT_TRUE(partial.stopped);
  EXPECT_EQ(partial.step, 5);
  ASSERT_TRUE(stopped.hasCheckpoint());

  session.resume = true;
  CountingObserver rest;
  TrainingOutcome resumed = trainRun(stopped, stopped.readConfig(), session, rest);
  EXPECT_FALSE(resumed.stopped);
  EXPECT_EQ(rest.firstStep, 5);
  EXPECT_EQ(readTextFile(stopped.sceneFile()), readTextFile(straight.sceneFile()));
  EXPECT_EQ(readTextFile(stopped.checkpointFile()), readTextFile(straight.checkpointFile()));
}

TEST_F(TrainingLoopTest, ACheckpointOfOtherSettingsIsRefused) {
  TrainConfig config = smallConfig();
  config.iters = 2;
  const RunFolder run(folder_->path() / "changed");
  run.create(config, false);
  CountingObserver quiet;
  trainRun(run, config, TrainingSession{}, quiet);
  config.backfaceSkip = 0.2f;
  TrainingSession session;
  session.resume = true;
  test::expectErrorNaming([&] { trainRun(run, config, session, quiet); }, run.checkpointFile(),
                          "was written with other settings");
}

TEST(RunFolder, ANewRunRefusesAFolderThatIsNotEmpty) {
  test::TempFolder folder;
  writeTextAtomically(folder.path() / "notes.txt", "mine\n");
  const RunFolder run(folder.path());
  test::expectErrorNaming([&] { run.create(TrainConfig(), false); }, folder.path(), "is not empty");
  run.create(TrainConfig(), true);
  EXPECT_EQ(toJson(run.readConfig()), toJson(TrainConfig()));
}

// Camera refinement's poses are part of the run's state: a run stopped between rounds and
// resumed ends where the straight run ends, poses and all.
TEST_F(TrainingLoopTest, ARefinedRunResumesBitForBitWithItsPoses) {
  TrainConfig config = smallConfig();
  config.cameras.every = 2;
  config.cameras.until = 6;
  TrainingSession session;
  session.evalViews = 2;

  const RunFolder straight(folder_->path() / "refined_straight");
  straight.create(config, false);
  CountingObserver all;
  trainRun(straight, config, session, all);
  const TrainingState finished = readCheckpoint(straight.checkpointFile());
  ASSERT_EQ(finished.cameraPoses.size(), 4u);  // refinement moved at least one of the 4 views

  const RunFolder stopped(folder_->path() / "refined_stopped");
  stopped.create(config, false);
  CountingObserver early(5);
  trainRun(stopped, config, session, early);
  ASSERT_EQ(readCheckpoint(stopped.checkpointFile()).cameraPoses.size(), 4u);
  session.resume = true;
  CountingObserver rest;
  trainRun(stopped, stopped.readConfig(), session, rest);
  EXPECT_EQ(rest.firstStep, 5);
  EXPECT_EQ(readTextFile(stopped.checkpointFile()), readTextFile(straight.checkpointFile()));
  EXPECT_EQ(readTextFile(stopped.sceneFile()), readTextFile(straight.sceneFile()));
}

}  // namespace
}  // namespace glint
