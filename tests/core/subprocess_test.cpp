// runProgram: merged output split into lines, exit status and signals, the child's
// environment and stdin, a stop signal passed on; findProgram on PATH.
#include "core/subprocess.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"

namespace glint {
namespace {

std::vector<std::string> linesOf(const ProgramRun& run, ProgramExit* exit) {
  std::vector<std::string> lines;
  *exit = runProgram(run, [&](std::string_view line) { lines.emplace_back(line); });
  return lines;
}

ProgramRun shell(const std::string& script) { return ProgramRun{"/bin/sh", {"-c", script}, {}}; }

TEST(FindProgram, FindsOnPathAndRefusesWhatIsNotThere) {
  std::optional<std::filesystem::path> sh = findProgram("sh");
  ASSERT_TRUE(sh.has_value());
  EXPECT_EQ(sh->filename(), "sh");
  EXPECT_FALSE(findProgram("glint-no-such-program-anywhere").has_value());
  EXPECT_TRUE(findProgram("/bin/sh").has_value());
  EXPECT_FALSE(findProgram("/no/such/folder/sh").has_value());
  EXPECT_FALSE(findProgram("/tmp").has_value());  // a folder is not a program
  EXPECT_FALSE(findProgram("").has_value());
}

TEST(RunProgram, MergesOutputAndErrorIntoLines) {
  ProgramExit exit;
  std::vector<std::string> lines = linesOf(shell("echo one; echo two >&2; printf 'three\\rfour\\n\\n'; printf five"), &exit);
  EXPECT_TRUE(exit.ok());
  // Empty lines are dropped; a carriage return ends a line as a newline does.
  EXPECT_EQ(lines, (std::vector<std::string>{"one", "two", "three", "four", "five"}));
}

TEST(RunProgram, ReportsTheExitStatusAndTheSignal) {
  ProgramExit exit;
  linesOf(shell("exit 3"), &exit);
  EXPECT_EQ(exit.status, 3);
  EXPECT_FALSE(exit.ok());
  EXPECT_EQ(describeExit(exit), "exited with status 3");
  linesOf(shell("kill -9 $$"), &exit);
  EXPECT_EQ(exit.signal, 9);
  EXPECT_NE(describeExit(exit).find("killed by signal 9"), std::string::npos) << describeExit(exit);
}

TEST(RunProgram, SetsTheChildsEnvironmentAndGivesItNoInput) {
  ProgramRun run = shell("echo \"$GLINT_TEST_VALUE\"; echo \"${HOME:+home kept}\"; cat; echo after");
  run.environment = {{"GLINT_TEST_VALUE", "first"}, {"GLINT_TEST_VALUE", "second"}};
  ProgramExit exit;
  std::vector<std::string> lines = linesOf(run, &exit);
  ASSERT_TRUE(exit.ok());
  // The last setting wins; the rest of the environment is kept; cat reads /dev/null and ends.
  EXPECT_EQ(lines, (std::vector<std::string>{"second", "home kept", "after"}));
}

TEST(RunProgram, AProgramThatCannotStartIsAnError) {
  ProgramRun run{"/no/such/program", {}, {}};
  try {
    runProgram(run, [](std::string_view) {});
    FAIL() << "started a program that does not exist";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/program: cannot start it"), std::string::npos) << e.what();
  }
}

TEST(RunProgram, PassesAStopSignalToTheChildAndWaitsForIt) {
  // SIGINT sent to this process alone (not to its process group) reaches a helper thread,
  // not necessarily the one waiting: the child must be stopped all the same. It is sent once
  // the child has said it runs, so that runProgram's handler is in place however slowly a
  // loaded machine starts it.
  std::atomic<bool> childRuns = false;
  std::thread sender([&] {
    while (!childRuns.load()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    kill(getpid(), SIGINT);
  });
  auto start = std::chrono::steady_clock::now();
  ProgramExit exit = runProgram(shell("echo running; sleep 20"), [&](std::string_view line) {
    if (line == "running") childRuns = true;
  });
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sender.join();
  EXPECT_TRUE(exit.interrupted);
  EXPECT_FALSE(exit.ok());
  EXPECT_EQ(exit.signal, SIGINT);
  EXPECT_LT(seconds, 10.0);
  EXPECT_EQ(describeExit(exit), "was interrupted");
}

}  // namespace
}  // namespace glint
