// MP4 videos from numbered PNG frames through the `ffmpeg` program, when it is installed.
#pragma once

#include <filesystem>
#include <optional>

namespace glint {

// The ffmpeg program on PATH, if any.
std::optional<std::filesystem::path> findFfmpeg();

// Encodes the frames named by framePattern (a printf pattern such as OUT/path/frame_%04d.png,
// numbered from 0) into an H.264 MP4 at fps frames per second, written atomically to output
// (odd image sizes are padded by one pixel, which H.264's 4:2:0 colour needs). Throws Error
// naming output with ffmpeg's last message when it fails.
void encodeVideo(const std::filesystem::path& ffmpeg, const std::filesystem::path& framePattern, int fps,
                 const std::filesystem::path& output);

}  // namespace glint
