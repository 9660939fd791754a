// Names what the program is doing, so that a failure with no message of its own (out of
// memory) can still be reported with its context: "out of memory while reading X".
#pragma once

#include <exception>
#include <string>

namespace glint {

// Marks a phase of work for the lifetime of the object ("reading scene.ply", "training
// step 1200 of out/run"). Scopes nest per thread. When an exception unwinds through a
// scope, the innermost such scope is remembered as the failed activity.
class ActivityScope {
 public:
  explicit ActivityScope(std::string description);
  ~ActivityScope();
  ActivityScope(const ActivityScope&) = delete;
  ActivityScope& operator=(const ActivityScope&) = delete;

  // Renames the phase (a loop's scope follows its step without a new object).
  void describe(std::string description);

 private:
  std::string description_;
  int uncaughtAtStart_;
};

// The innermost activity an exception unwound through since work last went on normally,
// or "" if none did. Read by main when it reports an exception without context.
std::string failedActivity();

// The one-line message for an exception that is not a glint::Error: allocation failures
// become "out of memory while <failedActivity>", others keep their text and gain the
// activity, so that no bare "std::bad_alloc" or "stoll" reaches the user.
std::string describeUnexpectedException(const std::exception& e);

}  // namespace glint
