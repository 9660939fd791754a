// The command line's habits end to end: bare `glint` fails with the command list, unknown
// flags and commands name the nearest known one, a missing or malformed flag is one line
// and exit status 1, every computing command takes --threads, and `train --view` stops
// serving when training ends unless --keep-serving.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/run_glint.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

class CliHabitsTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  test::TempFolder folder_;
};

TEST_F(CliHabitsTest, BareGlintListsTheCommandsAndFails) {
  Outcome bare = runGlint("");
  EXPECT_NE(bare.status, 0);
  for (const char* command : {"synth", "train", "render", "eval", "view"})
    EXPECT_NE(bare.output.find(command), std::string::npos) << command << "\n" << bare.output;
}

TEST_F(CliHabitsTest, AnUnknownFlagOrCommandNamesTheNearestOne) {
  Outcome flag = runGlint("train " + path("D") + " -o " + path("R") + " --iter 5");
  EXPECT_NE(flag.status, 0);
  EXPECT_NE(flag.output.find("unknown flag --iter; did you mean --iters?"), std::string::npos) << flag.output;
  EXPECT_FALSE(fs::exists(path("R")));

  Outcome render = runGlint("render scene.ply --sp 4");
  EXPECT_NE(render.status, 0);
  EXPECT_NE(render.output.find("did you mean --spp?"), std::string::npos) << render.output;

  Outcome command = runGlint("trian D -o R");
  EXPECT_NE(command.status, 0);
  EXPECT_NE(command.output.find("did you mean 'train'?"), std::string::npos) << command.output;
}

TEST_F(CliHabitsTest, AMissingOrMalformedFlagIsOneLineAndStatusOne) {
  Outcome missing = runGlint("train " + path("D"));
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_EQ(missing.output, "glint train: error: --output is required (see glint train --help)\n");
  Outcome malformed = runGlint("render " + path("scene.ply") + " --spp many");
  EXPECT_EQ(malformed.status, 1) << malformed.output;
  EXPECT_EQ(malformed.output.rfind("glint render: error: ", 0), 0u) << malformed.output;
  EXPECT_NE(malformed.output.find("--spp"), std::string::npos) << malformed.output;
  // --help is not an error.
  EXPECT_EQ(runGlint("train --help").status, 0);
}

TEST_F(CliHabitsTest, HelpFitsAHundredColumnsAndListsACommandPerLine) {
  const std::vector<std::string> commands = {"synth", "info", "sheet", "train",  "render",
                                             "eval",  "report", "export", "edit", "view"};
  for (const std::string& command : commands) {
    Outcome help = runGlint(command + " --help");
    ASSERT_EQ(help.status, 0) << command;
    std::istringstream lines(help.output);
    std::string line;
    int count = 0;
    while (std::getline(lines, line)) {
      ++count;
      EXPECT_LE(line.size(), 100u) << "glint " << command << " --help: " << line;
    }
    EXPECT_GT(count, 5) << command;
  }
  // `glint --help`: each command's summary on its own line (a summary that ran over would
  // go on in a line indented to the description column).
  Outcome top = runGlint("--help");
  ASSERT_EQ(top.status, 0);
  for (const std::string& command : commands) {
    const size_t at = top.output.find("\n  " + command + " ");
    ASSERT_NE(at, std::string::npos) << command << "\n" << top.output;
    const size_t end = top.output.find('\n', at + 1);
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(top.output.compare(end + 1, 10, std::string(10, ' ')), 0)
        << "the summary of " << command << " runs over a line:\n" << top.output;
  }
}

TEST_F(CliHabitsTest, EveryComputingCommandTakesThreads) {
  for (const char* command : {"synth", "info", "sheet", "train", "render", "eval", "edit", "view"}) {
    Outcome help = runGlint(std::string(command) + " --help");
    EXPECT_EQ(help.status, 0) << command;
    EXPECT_NE(help.output.find("--threads"), std::string::npos) << command << "\n" << help.output;
  }
  // The range is checked (render had no --threads before).
  Outcome tooMany = runGlint("render x.ply --threads 5000");
  EXPECT_NE(tooMany.status, 0);
  EXPECT_NE(tooMany.output.find("--threads"), std::string::npos) << tooMany.output;
}

TEST_F(CliHabitsTest, TrainViewStopsServingWhenTrainingEndsUnlessKeepServing) {
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 2 --test 1 --res 16x12 --spp 2");
  ASSERT_EQ(synth.status, 0) << synth.output;
  Outcome alone = runGlint("train " + path("D") + " -o " + path("K") + " --keep-serving");
  EXPECT_NE(alone.status, 0);
  EXPECT_NE(alone.output.find("--view"), std::string::npos) << alone.output;

  // Without --keep-serving the command returns once trained; the timeout ends it (status
  // 124) if it goes on serving.
  Outcome viewed = runGlint("train " + path("D") + " -o " + path("R") +
                                " --iters 3 --batch-rays 64 --threads 2 --eval-views 0 --view --view-port 0",
                            60);
  EXPECT_EQ(viewed.status, 0) << viewed.output;
  const std::string& output = viewed.output;
  EXPECT_NE(output.find("viewer at http"), std::string::npos) << output;
  EXPECT_NE(output.find("the viewer has stopped"), std::string::npos) << output;
}

}  // namespace
}  // namespace glint
