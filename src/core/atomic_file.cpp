// Atomic writes by rename, and whole-file reads with clear errors.
#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace glint {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& path, const std::function<void(const std::string&)>& write) {
  static std::atomic<int> counter{0};
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.parent_path().string(), "cannot create folder: " + ec.message());
  }
  // Keep the real extension last: some writers pick the format from it.
  std::string tempName = "." + path.stem().string() + ".tmp" + std::to_string(getpid()) + "_" +
                         std::to_string(counter.fetch_add(1)) + path.extension().string();
  fs::path temp = path.parent_path() / tempName;
  try {
    write(temp.string());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw Error(path.string(), "cannot move the finished file into place: " + ec.message());
  }
}

void writeTextAtomically(const fs::path& path, const std::string& contents) {
  writeAtomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw Error(path.string(), std::string("cannot open for writing: ") + std::strerror(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) throw Error(path.string(), "write failed (disk full?)");
  });
}

std::string readTextFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), fs::exists(path) ? "cannot open for reading" : "file not found");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace glint
