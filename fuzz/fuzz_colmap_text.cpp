// Fuzz harness for COLMAP's text model files (io/colmap_text.cpp) and the conversion of
// what they hold to Glint's cameras (scene/camera_conventions.cpp). The input is the
// three files separated by NUL bytes, which text files never contain: cameras.txt, then
// images.txt, then points3D.txt (missing ones are empty).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/colmap_camera_models.h"
#include "io/colmap_model.h"
#include "scene/camera_conventions.h"

namespace {

glint::ColmapFiles splitAtNul(const uint8_t* data, size_t size) {
  std::string input(reinterpret_cast<const char*>(data), size);
  std::string* parts[3];
  glint::ColmapFiles files;
  parts[0] = &files.cameras, parts[1] = &files.images, parts[2] = &files.points;
  size_t start = 0;
  for (int i = 0; i < 3 && start <= input.size(); ++i) {
    size_t end = i < 2 ? input.find('\0', start) : std::string::npos;
    if (end == std::string::npos) end = input.size();
    *parts[i] = input.substr(start, end - start);
    start = end + 1;
  }
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  glint::ColmapModel model;
  try {
    model = glint::parseColmapModel(splitAtNul(data, size), glint::ColmapFormat::Text, "fuzz");
    for (const glint::ColmapCamera& camera : model.cameras) glint::colmapPinholeIntrinsics(camera, "fuzz", "");
    glint::captureFromColmap(model);
  } catch (const glint::Error&) {  // a clean rejection
  }
  if (model.cameras.empty() && model.images.empty() && model.points.empty()) return 0;
  // What is accepted must write back and read again in both forms: an Error here escapes
  // and is a finding.
  for (glint::ColmapFormat format : {glint::ColmapFormat::Text, glint::ColmapFormat::Binary})
    glint::parseColmapModel(glint::formatColmapModel(model, format), format, "fuzz_again");
  return 0;
}
