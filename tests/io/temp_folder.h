// A uniquely named scratch folder under the system temp directory, removed with its contents.
#pragma once

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

namespace glint::test {

class TempFolder {
 public:
  TempFolder() {
    static std::atomic<int> counter{0};
    // pid + counter: unique across parallel test processes (ctest -j) and within one.
    path_ = std::filesystem::temp_directory_path() /
            ("glint_io_test_" + std::to_string(getpid()) + "_" + std::to_string(counter.fetch_add(1)));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Whole-file byte helpers for corrupting files in tests.
inline std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Keeps the first half of the file.
inline void truncateToHalf(const std::filesystem::path& path) {
  std::string bytes = readBytes(path);
  writeBytes(path, bytes.substr(0, bytes.size() / 2));
}

}  // namespace glint::test
