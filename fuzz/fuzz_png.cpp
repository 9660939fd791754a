// Fuzz harness for the PNG image reader (io/image_png.cpp, through readImage).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return glint::fuzz::parseAsFile(data, size, "png", ".png", [](const auto& path) { glint::readImage(path); });
}
