// Fuzz harness for COLMAP's binary model files (io/colmap_binary.cpp) and the conversion
// of what they hold to Glint's cameras (scene/camera_conventions.cpp). The input's first
// four bytes are the lengths of cameras.bin and images.bin (two little-endian uint16,
// cut to what is there); the rest is those two files, then points3D.bin.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/colmap_camera_models.h"
#include "io/colmap_model.h"
#include "scene/camera_conventions.h"

namespace {

glint::ColmapFiles splitByLengths(const uint8_t* data, size_t size) {
  glint::ColmapFiles files;
  if (size < 4) return files;
  size_t camerasLength = size_t(data[0]) | size_t(data[1]) << 8;
  size_t imagesLength = size_t(data[2]) | size_t(data[3]) << 8;
  std::string rest(reinterpret_cast<const char*>(data) + 4, size - 4);
  files.cameras = rest.substr(0, camerasLength);
  rest.erase(0, files.cameras.size());
  files.images = rest.substr(0, imagesLength);
  files.points = rest.substr(files.images.size());
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  glint::ColmapModel model;
  try {
    model = glint::parseColmapModel(splitByLengths(data, size), glint::ColmapFormat::Binary, "fuzz");
    for (const glint::ColmapCamera& camera : model.cameras) glint::colmapPinholeIntrinsics(camera, "fuzz", "");
    glint::captureFromColmap(model);
  } catch (const glint::Error&) {  // a clean rejection
  }
  if (model.cameras.empty() && model.images.empty() && model.points.empty()) return 0;
  // What is accepted must write back and read again in both forms: an Error here escapes
  // and is a finding.
  for (glint::ColmapFormat format : {glint::ColmapFormat::Binary, glint::ColmapFormat::Text})
    glint::parseColmapModel(glint::formatColmapModel(model, format), format, "fuzz_again");
  return 0;
}
