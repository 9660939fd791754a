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

// Writes text (or bytes) atomically.
void writeTextAtomically(const std::filesystem::path& path, const std::string& contents);

// Reads a whole file; throws Error naming the file if it cannot be read.
std::string readTextFile(const std::filesystem::path& path);

}  // namespace glint
