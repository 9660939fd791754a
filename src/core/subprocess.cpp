// Running another program with its merged output read line by line (posix_spawn and a pipe).
#include "core/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

extern char** environ;

namespace glint {

namespace fs = std::filesystem;

namespace {

volatile sig_atomic_t gStopSignal = 0;

void onStopSignal(int signal) { gStopSignal = signal; }

// SIGINT and SIGTERM only set a flag while a program runs, so that the child can be told and
// waited for; the previous handlers come back after.
class StopSignalGuard {
 public:
  StopSignalGuard() {
    gStopSignal = 0;
    struct sigaction action {};
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, &previousInt_);
    sigaction(SIGTERM, &action, &previousTerm_);
  }
  ~StopSignalGuard() {
    sigaction(SIGINT, &previousInt_, nullptr);
    sigaction(SIGTERM, &previousTerm_, nullptr);
  }
  StopSignalGuard(const StopSignalGuard&) = delete;
  StopSignalGuard& operator=(const StopSignalGuard&) = delete;

 private:
  struct sigaction previousInt_ {};
  struct sigaction previousTerm_ {};
};

// environ with `changes` applied: a name already present takes the new value.
std::vector<std::string> childEnvironment(const std::vector<std::pair<std::string, std::string>>& changes) {
  std::vector<std::string> entries;
  for (char** entry = environ; entry && *entry; ++entry) {
    std::string_view text(*entry);
    bool replaced = false;
    for (const auto& [name, value] : changes)
      if (text.size() > name.size() && text.substr(0, name.size()) == name && text[name.size()] == '=') replaced = true;
    if (!replaced) entries.emplace_back(text);
  }
  for (const auto& [name, value] : changes) entries.push_back(name + "=" + value);
  return entries;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> result;
  for (std::string& s : strings) result.push_back(s.data());
  result.push_back(nullptr);
  return result;
}

// Owns the spawn attributes and file actions so every exit path releases them.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
};

}  // namespace

std::optional<fs::path> findProgram(const std::string& name) {
  if (name.empty()) return std::nullopt;
  if (name.find('/') != std::string::npos) {
    if (access(name.c_str(), X_OK) == 0 && !fs::is_directory(name)) return fs::path(name);
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/local/bin:/usr/bin:/bin";
  while (true) {
    size_t colon = rest.find(':');
    std::string_view folder = rest.substr(0, colon);
    fs::path candidate = fs::path(folder.empty() ? "." : std::string(folder)) / name;
    std::error_code ignored;
    if (access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate, ignored)) return candidate;
    if (colon == std::string_view::npos) break;
    rest = rest.substr(colon + 1);
  }
  return std::nullopt;
}

ProgramExit runProgram(const ProgramRun& run, const std::function<void(std::string_view line)>& onLine) {
  int pipeEnds[2];
  if (pipe2(pipeEnds, O_CLOEXEC) != 0)
    throw Error(run.program.string(), std::string("cannot start it: no pipe (") + std::strerror(errno) + ")");
  SpawnSetup setup;
  posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&setup.actions, pipeEnds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&setup.actions, pipeEnds[1], STDERR_FILENO);
  // The child starts with the default actions for the signals this process may catch.
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  // Its own process group, so that a stop reaches the program's children too (a shell's
  // command, COLMAP's helpers); Ctrl-C at the terminal reaches this process, which passes
  // it on.
  posix_spawnattr_setpgroup(&setup.attributes, 0);
  posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);

  std::vector<std::string> argumentStrings{run.program.string()};
  argumentStrings.insert(argumentStrings.end(), run.arguments.begin(), run.arguments.end());
  std::vector<std::string> environmentStrings = childEnvironment(run.environment);
  std::vector<char*> argv = pointers(argumentStrings);
  std::vector<char*> envp = pointers(environmentStrings);

  StopSignalGuard signals;
  pid_t child = 0;
  int spawnError = posix_spawn(&child, run.program.c_str(), &setup.actions, &setup.attributes, argv.data(), envp.data());
  close(pipeEnds[1]);
  if (spawnError != 0) {
    close(pipeEnds[0]);
    throw Error(run.program.string(), std::string("cannot start it: ") + std::strerror(spawnError));
  }

  ProgramExit exit;
  bool forwarded = false;
  std::string pending;
  char buffer[4096];
  auto forwardStop = [&]() {
    if (gStopSignal == 0 || forwarded) return;
    exit.interrupted = true;
    kill(-child, gStopSignal);
    forwarded = true;
  };
  while (true) {
    // The signal may land on any of this process's threads, so the flag is looked at every
    // 100 ms rather than only when a read is interrupted.
    pollfd readable{pipeEnds[0], POLLIN, 0};
    int ready = poll(&readable, 1, 100);
    forwardStop();
    if (ready == 0 || (ready < 0 && errno == EINTR)) continue;
    ssize_t n = ready < 0 ? -1 : read(pipeEnds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    pending.append(buffer, size_t(n));
    size_t start = 0;
    for (size_t i = 0; i < pending.size(); ++i) {
      if (pending[i] != '\n' && pending[i] != '\r') continue;
      if (i > start) onLine(std::string_view(pending).substr(start, i - start));
      start = i + 1;
    }
    pending.erase(0, start);
  }
  if (!pending.empty()) onLine(pending);
  close(pipeEnds[0]);

  int raw = 0;
  while (waitpid(child, &raw, 0) < 0 && errno == EINTR) forwardStop();
  if (gStopSignal != 0) exit.interrupted = true;
  if (WIFEXITED(raw)) exit.status = WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) exit.signal = WTERMSIG(raw);
  return exit;
}

std::string describeExit(const ProgramExit& exit) {
  if (exit.interrupted) return "was interrupted";
  if (exit.signal != 0)
    return "was killed by signal " + std::to_string(exit.signal) + " (" + strsignal(exit.signal) + ")";
  return "exited with status " + std::to_string(exit.status);
}

}  // namespace glint
