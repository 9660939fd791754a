// Fuzz harness for the JPEG image reader (io/image_jpeg.cpp, through readImage).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return glint::fuzz::parseAsFile(data, size, "jpeg", ".jpg", [](const auto& path) { glint::readImage(path); });
}
