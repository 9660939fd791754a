// Writes files atomically (temporary file in the same folder, then rename), so a crash or
// Ctrl-C never leaves a half-written output or destroys the previous one.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace glint {

// Calls write(tempPath) to produce the file, then renames it over path. If write throws,
// the temporary file is removed and the exception propagates; path is untouched. The
// first write into a folder also removes the temporaries of processes that died there.
void writeAtomically(const std::filesystem::path& path, const std::function<void(const std::string& tempPath)>& write);

// Throws Error unless `path` is absent or a regular file: an output replaces regular files
// only, never a device, a folder, a FIFO, a socket or a symbolic link (the rename would put a
// regular file in the place of what the user made). writeAtomically checks it; commands call
// it first too, to fail before the work.
void checkReplaceableOutput(const std::filesystem::path& path);

// Writes text (or bytes) atomically.
void writeTextAtomically(const std::filesystem::path& path, const std::string& contents);

// Reads a whole file through readInputFile (core/input_file.h): a regular file of at most
// kMaxTextModelFileBytes; throws Error naming the file otherwise.
std::string readTextFile(const std::filesystem::path& path);

}  // namespace glint
