// Runs ffmpeg without a shell (core/subprocess), so file names need no quoting.
#include "app/video_encoder.h"

#include <string>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/subprocess.h"

namespace glint {

namespace fs = std::filesystem;

std::optional<fs::path> findFfmpeg() { return findProgram("ffmpeg"); }

void encodeVideo(const fs::path& ffmpeg, const fs::path& framePattern, int fps, const fs::path& output) {
  writeAtomically(output, [&](const std::string& tempPath) {
    ProgramRun run{ffmpeg,
                   {"-nostdin", "-y", "-loglevel", "error", "-framerate", std::to_string(fps), "-start_number", "0",
                    "-i", framePattern.string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
                    "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", tempPath},
                   {}};
    std::string message;  // ffmpeg's last line: its error
    ProgramExit exit = runProgram(run, [&](std::string_view line) { message = line; });
    if (!exit.ok())
      throw Error(output.string(), "ffmpeg failed to encode " + framePattern.string() +
                                       (message.empty() ? " (it " + describeExit(exit) + ")" : ": " + message));
  });
}

}  // namespace glint
