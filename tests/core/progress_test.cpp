// Tests of duration formatting and of progress bars advanced from many threads.
#include "core/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <thread>

#include "core/parallel.h"

namespace glint {
namespace {

// Sets or clears GLINT_QUIET for one scope and restores the previous value afterwards,
// so the other tests in this process see the environment they started with.
class ScopedQuiet {
 public:
  explicit ScopedQuiet(bool quiet) {
    if (const char* old = std::getenv("GLINT_QUIET")) old_ = old;
    if (quiet) setenv("GLINT_QUIET", "1", 1);
    else unsetenv("GLINT_QUIET");
  }
  ~ScopedQuiet() {
    if (old_) setenv("GLINT_QUIET", old_->c_str(), 1);
    else unsetenv("GLINT_QUIET");
  }

 private:
  std::optional<std::string> old_;
};

int countLines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

TEST(FormatDuration, MinutesAndSeconds) {
  EXPECT_EQ(formatDuration(0), "00:00");
  EXPECT_EQ(formatDuration(5), "00:05");
  EXPECT_EQ(formatDuration(75), "01:15");
  EXPECT_EQ(formatDuration(3599), "59:59");
}

TEST(FormatDuration, HoursWhenAtLeastOneHour) {
  EXPECT_EQ(formatDuration(3600), "1:00:00");
  EXPECT_EQ(formatDuration(3725), "1:02:05");
  EXPECT_EQ(formatDuration(36000 + 59 * 60 + 59), "10:59:59");
}

TEST(FormatDuration, RoundsToTheNearestSecond) {
  EXPECT_EQ(formatDuration(0.4), "00:00");
  EXPECT_EQ(formatDuration(59.6), "01:00");
  EXPECT_EQ(formatDuration(3599.6), "1:00:00");
}

TEST(FormatDuration, UnknownDurations) {
  EXPECT_EQ(formatDuration(std::nan("")), "--:--");
  EXPECT_EQ(formatDuration(-1), "--:--");
  EXPECT_EQ(formatDuration(INFINITY), "--:--");
}

TEST(ProgressBar, QuietBarAdvancedFromManyThreads) {
  ScopedQuiet quiet(true);
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("quiet work", 10000, "items");
    parallelFor(10000, 7, [&](int64_t i) {
      bar.advance();
      if (i % 1000 == 0) bar.setStatus("at " + std::to_string(i));
    });
    bar.finish();
    bar.finish();  // idempotent
  }                // and the destructor after finish() draws nothing more
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(ProgressBar, LoggedBarPrintsOneFinalLineWhenFinishedTwice) {
  ScopedQuiet quiet(false);
  // Capturing stderr makes it a file rather than a terminal: the bar logs plain lines.
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("logged work", 5000, "views");
    EXPECT_FALSE(ProgressBar::interactive());
    parallelFor(5000, 3, [&](int64_t) { bar.advance(); });
    bar.setStatus("loss 0.25");
    bar.finish();
    bar.finish();
  }
  std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(countLines(out), 1) << out;
  EXPECT_NE(out.find("logged work"), std::string::npos) << out;
  EXPECT_NE(out.find("5000/5000 views"), std::string::npos) << out;
  EXPECT_NE(out.find("100%"), std::string::npos) << out;
  EXPECT_NE(out.find("loss 0.25"), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << "no carriage returns in logs";
}

TEST(ProgressBar, DestructorFinishesAndOvershootIsClamped) {
  ScopedQuiet quiet(false);
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("overshoot", 10);
    bar.advance(25);  // more than the total: shown as complete, never above 100%
  }
  std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(countLines(out), 1) << out;
  EXPECT_NE(out.find("10/10 it"), std::string::npos) << out;
  EXPECT_NE(out.find("100%"), std::string::npos) << out;
}

TEST(ProgressBar, EmptyTotalIsComplete) {
  ScopedQuiet quiet(false);
  ::testing::internal::CaptureStderr();
  { ProgressBar bar("nothing to do", 0); }
  std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(out.find("100%"), std::string::npos) << out;
  EXPECT_NE(out.find("0/0"), std::string::npos) << out;
}


// A resumed job's earlier units count toward the fraction but not the rate: 4 units in
// about 0.2 s after resuming at 996 is about 20 units/s, not 5000 (and the rate's
// unit count is what a resumed `glint train` shows).
TEST(ProgressBar, RateAfterResumeCountsOnlyTheNewUnits) {
  ScopedQuiet quiet(false);
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("resumed", 1000, "steps");
    bar.resumeAt(996);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    bar.advance(4);
  }
  std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(out.find("1000/1000 steps"), std::string::npos) << out;
  const size_t rate = out.find(" steps/s");
  ASSERT_NE(rate, std::string::npos) << out;
  const size_t from = out.rfind(' ', rate - 1) + 1;
  const std::string number = out.substr(from, rate - from);
  ASSERT_EQ(number.find_first_not_of("0123456789."), std::string::npos) << "a k or M rate: " << out;
  const double perSecond = std::stod(number);
  EXPECT_LT(perSecond, 25.0) << out;  // 996 + 4 units in 0.2 s would be 5000
  EXPECT_GT(perSecond, 1.0) << out;
}

}  // namespace
}  // namespace glint
