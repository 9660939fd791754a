// The NeRF/Blender camera file transforms_{split}.json (docs/data-format.md): parsing with
// strict checks, and pretty-printed atomic writing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "math/mat4.h"

namespace glint {

// One entry of "frames".
struct TransformsFrame {
  std::string filePath;  // relative to the dataset root, without "./" and image extension
  Mat4 transformMatrix;  // camera-to-world, OpenGL camera axes, rigid
};

struct TransformsFile {
  double cameraAngleX = 0;  // horizontal field of view, radians, in (0, pi)
  std::vector<TransformsFrame> frames;
};

// Parses the text of a transforms file; fileName is used in error messages only. Checks:
// camera_angle_x is a number in (0, pi); every frame has a string file_path and a
// transform_matrix of 4 rows of 4 finite numbers, last row (0 0 0 1) within 1e-4 and a
// rotation (orthonormal within 1e-3, determinant +1) in its upper 3x3; file_paths are
// unique. Unknown keys are ignored. "./" prefixes and .png/.exr/.tif/.tiff extensions are
// stripped from file_path, and frames are returned sorted by file_path (an empty frames
// list is returned as such). Throws Error naming the file, the frame index (position in
// the file) and the key.
TransformsFile parseTransformsJson(const std::string& text, const std::string& fileName);
// Reads and parses a transforms file; throws Error naming the file if it is missing.
TransformsFile readTransformsJson(const std::filesystem::path& path);

// JSON text with indent 2, each matrix row on one line, numbers at full (round-trip)
// precision; frames in the given order.
std::string formatTransformsJson(const TransformsFile& transforms);
// Writes formatTransformsJson atomically.
void writeTransformsJson(const std::filesystem::path& path, const TransformsFile& transforms);

}  // namespace glint
