// Fuzz harness for the NeRF camera file transforms_{split}.json (io/transforms_json.cpp).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/transforms_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    glint::TransformsFile parsed = glint::parseTransformsJson(text, "transforms_fuzz.json");
    // What is accepted must also write back: formatting sees every parsed value.
    glint::formatTransformsJson(parsed);
  } catch (const glint::Error&) {  // a clean rejection
  }
  return 0;
}
