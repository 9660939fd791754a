// Fuzz harness for PLY (binary of either byte order, and ASCII): the generic table reader,
// Gaussian scenes and point clouds.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz/fuzz_support.h"
#include "io/point_cloud.h"
#include "scene/gaussian_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The two readers interpret the same table differently, so both see every input.
  return glint::fuzz::parseAsFile(data, size, "ply", ".ply", [](const auto& path) {
    try {
      glint::readGaussianPly(path);
    } catch (const glint::Error&) {
    }
    glint::readPointCloud(path);
  });
}
