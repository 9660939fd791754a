// Fuzz harness for nerfstudio's transforms.json (io/nerfstudio_transforms.cpp) and the
// conversion of its frames to Glint's cameras (scene/camera_conventions.cpp).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/nerfstudio_transforms.h"
#include "scene/camera_conventions.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  glint::NerfstudioTransforms parsed;
  try {
    parsed = glint::parseNerfstudioTransforms(text, "transforms_fuzz.json");
  } catch (const glint::Error&) {  // a clean rejection
    return 0;
  }
  glint::captureFromNerfstudio(parsed);
  // What is accepted must write back and read again: an Error here escapes and is a finding.
  glint::parseNerfstudioTransforms(glint::formatNerfstudioTransforms(parsed), "transforms_fuzz_again.json");
  return 0;
}
