// Running another program (COLMAP) with its output read line by line as it comes.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

// The full path of an executable found on PATH (as a shell would: the first match), or
// nullopt. A name holding a slash is taken as a path and only checked to be executable.
std::optional<std::filesystem::path> findProgram(const std::string& name);

struct ProgramExit {
  int status = 0;  // the exit status when the program exited by itself
  int signal = 0;  // the signal that ended it, or 0
  bool interrupted = false;  // Ctrl-C (SIGINT) or SIGTERM reached this process while it ran
  bool ok() const { return status == 0 && signal == 0 && !interrupted; }
};

struct ProgramRun {
  std::filesystem::path program;
  std::vector<std::string> arguments;                       // without the program itself
  std::vector<std::pair<std::string, std::string>> environment;  // set (or replaced) for the child only
};

// Runs `run` and waits for it. Its standard output and error are merged and passed to onLine
// one line at a time (without the newline; a carriage return also ends a line, so progress
// redrawn in place arrives as lines too). Standard input is /dev/null.
//
// The program runs in a process group of its own. A SIGINT or SIGTERM that reaches this
// process while it runs (Ctrl-C at the terminal included) is passed on to that group; the
// program is waited for and the result says `interrupted`, so the caller can clean up
// before it stops. Throws Error when the program cannot be started.
ProgramExit runProgram(const ProgramRun& run, const std::function<void(std::string_view line)>& onLine);

// "exited with status 3" or "was killed by signal 9 (Killed)" or "was interrupted".
std::string describeExit(const ProgramExit& exit);

}  // namespace glint
