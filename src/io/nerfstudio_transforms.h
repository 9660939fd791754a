// nerfstudio's transforms.json (one file for all frames, intrinsics global or per frame):
// strict parsing and writing (docs/capture-format.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "math/mat4.h"

namespace glint {

// One entry of "frames", with the intrinsics that apply to it resolved (its own keys
// override the file's global ones).
struct NerfstudioFrame {
  std::string filePath;  // as written, without a leading "./"; relative to the file's folder
  Mat4 transformMatrix;  // camera-to-world, OpenGL camera axes (x right, y up, looking down -z), rigid
  int width = 0, height = 0;  // "w", "h"
  // Pixels, principal point from the image's top-left corner: nerfstudio, like COLMAP,
  // puts the centre of pixel (i, j) at (i + 0.5, j + 0.5).
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::string depthFilePath;  // "depth_file_path", or empty
  std::string maskPath;       // "mask_path", or empty
};

struct NerfstudioTransforms {
  std::vector<NerfstudioFrame> frames;  // sorted by filePath, as nerfstudio sorts them
  // "applied_transform": the transform nerfstudio's ns-process-data applied to COLMAP's
  // world to make the world of transform_matrix (x_here = appliedTransform x_colmap; it
  // swaps y and z and negates the new z, so that z points up). Identity when absent.
  // Cameras are used in this file's world as they are; this maps COLMAP points into it.
  Mat4 appliedTransform = Mat4::identity();
  bool hasAppliedTransform = false;
  std::string plyFilePath;  // "ply_file_path", or empty
};

// Parses the text of a transforms.json; fileName is used in error messages only. Keys,
// each global or per frame (the frame's wins): fl_x (or camera_angle_x, the horizontal
// field of view in radians, giving fl_x = w / (2 tan(camera_angle_x / 2))), fl_y (or
// camera_angle_y, else fl_x), cx, cy (else w/2, h/2), w, h; per frame: file_path,
// transform_matrix (4x4, rigid, last row 0 0 0 1), depth_file_path, mask_path. Refused:
// camera_model other than OPENCV, PINHOLE or SIMPLE_PINHOLE; a non-zero distortion
// coefficient k1..k6, p1, p2 (the error suggests undistorting); paths that are absolute
// or leave the folder; duplicate file_paths. Unknown keys are ignored. Throws Error
// naming the file, the frame index (its position in the file) and the key.
NerfstudioTransforms parseNerfstudioTransforms(const std::string& text, const std::string& fileName);
// Reads and parses a transforms.json; throws Error naming the file if it is missing.
NerfstudioTransforms readNerfstudioTransforms(const std::filesystem::path& path);

// JSON text with camera_model "PINHOLE", intrinsics per frame, applied_transform (3x4)
// when present, numbers at full round-trip precision; frames in the given order.
std::string formatNerfstudioTransforms(const NerfstudioTransforms& transforms);
// Writes formatNerfstudioTransforms atomically.
void writeNerfstudioTransforms(const std::filesystem::path& path, const NerfstudioTransforms& transforms);

}  // namespace glint
