// A terminal progress bar with rate and ETA for long loops; safe to advance from many threads.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace glint {

class ProgressBar {
 public:
  // label: what is being done; total: number of units; unit: their name ("views", "rays").
  ProgressBar(std::string label, int64_t total, std::string unit = "");
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Adds n finished units; redraws at most a few times per second.
  void advance(int64_t n = 1);
  // Starts the count at `done` units finished before this bar (a resumed job): they show in
  // the count and the fraction, but the rate and the remaining time count only the units
  // done since. Call before the first advance().
  void resumeAt(int64_t done);
  // Draws the final state and ends the line. Called by the destructor if not before.
  void finish();
  // Extra text shown after the bar (e.g. current loss); thread-safe.
  void setStatus(const std::string& status);
  // Prints a message on its own line above the bar (an event worth keeping in the log);
  // printed even when the bar itself is silent, except under GLINT_QUIET.
  void note(const std::string& message);

  // Progress bars are silent when GLINT_QUIET is set or stderr is not a terminal
  // (in which case one line is printed every ~10 s so logs still show progress).
  static bool interactive();

 private:
  void draw(bool final);

  std::string label_;
  std::string unit_;
  std::string status_;
  int64_t total_;
  std::atomic<int64_t> done_{0};
  int64_t doneBefore_ = 0;  // resumeAt's units, left out of the rate
  std::chrono::steady_clock::time_point start_;
  // Atomic: advance() reads it without the lock while the thread that draws updates it.
  std::atomic<std::chrono::steady_clock::time_point> lastDraw_;
  std::mutex mutex_;
  bool finished_ = false;
  bool interactive_;
  bool quiet_;
};

// "1:02:03" or "02:03" for a duration in seconds.
std::string formatDuration(double seconds);

}  // namespace glint
