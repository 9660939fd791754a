// The failed-activity record behind ActivityScope.
#include "core/activity.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <stdexcept>
#include <utility>

#include "core/input_file.h"

namespace glint {

namespace {

std::mutex gMutex;
std::string gFailed;  // guarded by gMutex

}  // namespace

ActivityScope::ActivityScope(std::string description)
    : description_(std::move(description)), uncaughtAtStart_(std::uncaught_exceptions()) {
  // New work begins: whatever failed before was handled, so it is no longer the context.
  std::lock_guard<std::mutex> lock(gMutex);
  gFailed.clear();
}

ActivityScope::~ActivityScope() {
  if (std::uncaught_exceptions() <= uncaughtAtStart_) return;
  // Unwinding: inner scopes are destroyed first, so the first one recorded is the innermost.
  std::lock_guard<std::mutex> lock(gMutex);
  if (gFailed.empty()) gFailed = description_;
}

void ActivityScope::describe(std::string description) { description_ = std::move(description); }

std::string failedActivity() {
  std::lock_guard<std::mutex> lock(gMutex);
  return gFailed;
}

namespace {

double physicalMemoryGiB() {
  long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? double(pages) * double(pageSize) / double(1ull << 30) : 0.0;
}

}  // namespace

std::string describeUnexpectedException(const std::exception& e) {
  std::string activity = failedActivity();
  std::string context = activity.empty() ? "" : " while " + activity;
  // length_error comes from containers asked for more elements than they can hold: a size
  // taken from a file or flag, not a programming error the user could act on otherwise.
  bool allocation = dynamic_cast<const std::bad_alloc*>(&e) != nullptr ||
                    dynamic_cast<const std::length_error*>(&e) != nullptr;
  // The standard library's file errors quote whole paths (a hostile name can be megabytes).
  if (const auto* file = dynamic_cast<const std::filesystem::filesystem_error*>(&e)) {
    const std::string what = file->code().value() == ENAMETOOLONG ? "the name is too long for the file system"
                                                                   : file->code().message();
    return quotedPath(file->path1()) + ": " + what + context;
  }
  if (!allocation) return e.what() + (context.empty() ? "" : " (" + context.substr(1) + ")");
  char memory[64];
  std::snprintf(memory, sizeof(memory), "%.1f GiB", physicalMemoryGiB());
  return "out of memory" + context + " (this machine has " + memory +
         "; a smaller input, resolution or Gaussian count needs less)";
}

}  // namespace glint
