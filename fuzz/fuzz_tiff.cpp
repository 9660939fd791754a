// Fuzz harness for the TIFF image reader (io/image_tiff.cpp, through readImage).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return glint::fuzz::parseAsFile(data, size, "tiff", ".tiff", [](const auto& path) { glint::readImage(path); });
}
