// Progress bar drawing: label, bar, count, rate, elapsed and remaining time.
#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace glint {

namespace {
constexpr double kRedrawSeconds = 0.2;
constexpr double kLogSeconds = 10.0;  // when stderr is not a terminal
constexpr int kBarWidth = 28;

std::string formatRate(double perSecond, const std::string& unit) {
  char buffer[64];
  if (perSecond >= 1e6) std::snprintf(buffer, sizeof buffer, "%.2fM %s/s", perSecond / 1e6, unit.c_str());
  else if (perSecond >= 1e3) std::snprintf(buffer, sizeof buffer, "%.1fk %s/s", perSecond / 1e3, unit.c_str());
  else std::snprintf(buffer, sizeof buffer, "%.2f %s/s", perSecond, unit.c_str());
  return buffer;
}
}  // namespace

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  long s = std::lround(seconds);
  char buffer[32];
  if (s >= 3600) std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(buffer, sizeof buffer, "%02ld:%02ld", s / 60, s % 60);
  return buffer;
}

bool ProgressBar::interactive() { return isatty(STDERR_FILENO) != 0; }

ProgressBar::ProgressBar(std::string label, int64_t total, std::string unit)
    : label_(std::move(label)),
      unit_(unit.empty() ? "it" : std::move(unit)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_),
      interactive_(interactive()),
      quiet_(std::getenv("GLINT_QUIET") != nullptr) {
  if (interactive_ && !quiet_) draw(false);
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::setStatus(const std::string& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  status_ = status;
}

void ProgressBar::note(const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (quiet_) return;
  if (interactive_) {
    std::fprintf(stderr, "\r\033[2K%s: %s\n", label_.c_str(), message.c_str());
    if (!finished_) draw(false);
  } else {
    std::fprintf(stderr, "%s: %s\n", label_.c_str(), message.c_str());
  }
  std::fflush(stderr);
}

void ProgressBar::advance(int64_t n) {
  done_.fetch_add(n, std::memory_order_relaxed);
  if (quiet_) return;
  auto now = std::chrono::steady_clock::now();
  double sinceDraw = std::chrono::duration<double>(now - lastDraw_.load(std::memory_order_relaxed)).count();
  if (sinceDraw < (interactive_ ? kRedrawSeconds : kLogSeconds)) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_) return;
  lastDraw_.store(now, std::memory_order_relaxed);
  draw(false);
}

void ProgressBar::resumeAt(int64_t done) {
  std::lock_guard<std::mutex> lock(mutex_);
  doneBefore_ = done;
  done_.store(done, std::memory_order_relaxed);
  start_ = std::chrono::steady_clock::now();
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (!quiet_) draw(true);
}

void ProgressBar::draw(bool final) {
  int64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double fraction = total_ > 0 ? double(done) / double(total_) : 1.0;
  double rate = elapsed > 0 ? double(std::max<int64_t>(done - doneBefore_, 0)) / elapsed : 0.0;
  double remaining = rate > 0 ? double(total_ - done) / rate : NAN;

  std::string bar(kBarWidth, ' ');
  int filled = static_cast<int>(fraction * kBarWidth);
  for (int i = 0; i < filled; ++i) bar[i] = '#';

  char line[512];
  std::snprintf(line, sizeof line, "%s [%s] %3d%% %lld/%lld %s | %s | %s %s", label_.c_str(), bar.c_str(),
                static_cast<int>(fraction * 100), static_cast<long long>(done), static_cast<long long>(total_),
                unit_.c_str(), formatRate(rate, unit_).c_str(), formatDuration(elapsed).c_str(),
                final ? "total" : ("ETA " + formatDuration(remaining)).c_str());
  std::string text = line;
  if (!status_.empty()) text += " | " + status_;
  if (interactive_) std::fprintf(stderr, "\r\033[2K%s%s", text.c_str(), final ? "\n" : "");
  else std::fprintf(stderr, "%s\n", text.c_str());
  std::fflush(stderr);
}

}  // namespace glint
