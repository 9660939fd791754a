// The one way Glint opens an input file: regular files only, a size limit checked before
// reading, and errors that name the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace glint {

// Size limits by kind of input, checked against the file's size before a byte is read.
// Generous for real data (a COLMAP points3D.txt of a large reconstruction is hundreds of
// MB), small enough that a mistaken file fails at once instead of filling memory.
constexpr uint64_t kMaxJsonFileBytes = uint64_t(256) << 20;       // transforms, capture.json, configs
constexpr uint64_t kMaxTextModelFileBytes = uint64_t(4) << 30;    // COLMAP models, CSV logs
constexpr uint64_t kMaxBinaryInputFileBytes = uint64_t(64) << 30; // images, PLY, checkpoints, glTF

// Checks that `path` names a regular file (a symbolic link is followed: docs/capture-format.md)
// of at most maxBytes, and returns its size. Throws Error naming the file for a missing
// file, a folder, a FIFO, a device or a socket, a file over the limit, or a name the system
// refuses (too long). Never blocks: nothing is opened.
uint64_t checkInputFile(const std::filesystem::path& path, uint64_t maxBytes = kMaxBinaryInputFileBytes);

// The whole contents of a checked input file. A FIFO put in place of the file after the
// check is still refused: the file is opened without blocking and checked again.
std::string readInputFile(const std::filesystem::path& path, uint64_t maxBytes);

// True when something has this name: a file, a folder, a device, a link (even a broken one).
// What decides that an input is there, so that a FIFO or a broken link in its place is
// reported as itself when read, not taken for a missing file. Never throws.
bool pathPresent(const std::filesystem::path& path);

// `path` quoted for a message: printable, and a very long name cut with its length.
std::string quotedPath(const std::filesystem::path& path);

}  // namespace glint
