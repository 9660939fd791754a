// What the fuzz harnesses share: the fuzz input as a file for parsers that only read paths,
// and a small Gaussian scene for harnesses that apply what they parse.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/gaussians.h"

namespace glint::fuzz {

// The input bytes written to /tmp/glint_fuzz_<pid>_<stem><extension>, removed again when
// this goes out of scope. One file per process, so that parallel fuzzers (-jobs) and the
// CTest replays never share one; the extension is kept because readers dispatch on it.
class TempInputFile {
 public:
  TempInputFile(const uint8_t* data, size_t size, const std::string& stem, const std::string& extension)
      : path_(std::filesystem::temp_directory_path() /
              ("glint_fuzz_" + std::to_string(::getpid()) + "_" + stem + extension)) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  ~TempInputFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TempInputFile(const TempInputFile&) = delete;
  TempInputFile& operator=(const TempInputFile&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The body of a harness whose parser reads a file: parse(path) on the input written with
// the given extension. A glint::Error is a clean rejection; anything else escapes and is
// a finding.
template <typename Parse>
int parseAsFile(const uint8_t* data, size_t size, const std::string& stem, const std::string& extension,
                Parse parse) {
  TempInputFile file(data, size, stem, extension);
  try {
    parse(file.path());
  } catch (const Error&) {
  }
  return 0;
}

// 27 Gaussians on a 3x3x3 grid in [-1, 1]^3 with varied attributes, so that selections
// and filters of a fuzzed edit have something to keep and something to drop.
inline GaussianScene smallScene() {
  GaussianScene scene;
  scene.resize(27);
  for (size_t i = 0; i < scene.size(); ++i) {
    float x = float(i % 3) - 1.0f, y = float(i / 3 % 3) - 1.0f, z = float(i / 9) - 1.0f;
    scene.position[i] = {x, y, z};
    scene.logScale[i] = Vec3f(-2.0f);
    scene.opacityLogit[i] = x;
    scene.diffuse[i] = {0.5f + 0.25f * x, 0.5f + 0.25f * y, 0.5f + 0.25f * z};
    scene.normal[i] = {0, 1, 0};
    scene.roughness[i] = float(i) / 26.0f;
  }
  return scene;
}

}  // namespace glint::fuzz
