// Runs ffmpeg without a shell (posix_spawn), so file names need no quoting.
#include "app/video_encoder.h"

#include <spawn.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

extern char** environ;

namespace glint {

namespace fs = std::filesystem;

std::optional<fs::path> findFfmpeg() {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    fs::path candidate = fs::path(folder) / "ffmpeg";
    if (access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate;
  }
  return std::nullopt;
}

namespace {

// The last non-empty line of a text file (ffmpeg's error), or "" when there is none.
std::string lastLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

}  // namespace

void encodeVideo(const fs::path& ffmpeg, const fs::path& framePattern, int fps, const fs::path& output) {
  writeAtomically(output, [&](const std::string& tempPath) {
    fs::path log = tempPath + ".log";
    std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-y", "-loglevel", "error",
                                     "-framerate", std::to_string(fps), "-start_number", "0",
                                     "-i", framePattern.string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v", "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
                                     "-f", "mp4", tempPath};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw Error(output.string(), "could not start " + ffmpeg.string());
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    std::string message = lastLine(log);
    std::error_code ignored;
    fs::remove(log, ignored);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw Error(output.string(), "ffmpeg failed to encode " + framePattern.string() +
                                       (message.empty() ? "" : ": " + message));
  });
}

}  // namespace glint
