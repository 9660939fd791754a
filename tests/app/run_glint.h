// Runs the glint program built with the tests (GLINT_BINARY) and captures its output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace glint::test {

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr together
};

// With timeoutSeconds > 0 the program is stopped after that long (coreutils' timeout:
// status 124), for tests of commands that could otherwise hang. `environment` is shell
// assignments for the program ("NAME=value OTHER=value").
inline Outcome runGlint(const std::string& args, int timeoutSeconds = 0, const std::string& environment = "") {
  std::string command = (environment.empty() ? std::string() : environment + " ") +
                        (timeoutSeconds > 0 ? "timeout " + std::to_string(timeoutSeconds) + " " : std::string()) +
                        std::string(GLINT_BINARY) + " " + args + " 2>&1";
  Outcome run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  int raw = pclose(pipe);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

}  // namespace glint::test
