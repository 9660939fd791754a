// Fuzz harness for the glTF importer (synth/gltf_import.cpp): .gltf text and .glb binaries.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "synth/gltf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The importer tells .glb from .gltf by the magic bytes, not by the extension.
  return glint::fuzz::parseAsFile(data, size, "gltf", ".gltf", [](const auto& path) { glint::loadGltfScene(path); });
}
