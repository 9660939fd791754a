// COLMAP sparse models (cameras, images, points3D) in their text and binary forms:
// strict parsing, and writing for fixtures and round trips (docs/capture-format.md).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "math/quat.h"
#include "math/vec.h"

namespace glint {

// One line of cameras.txt / record of cameras.bin.
struct ColmapCamera {
  uint32_t id = 0;
  std::string model;           // COLMAP's model name, e.g. "PINHOLE"
  int width = 0, height = 0;   // pixels
  std::vector<double> params;  // as many as the model takes (io/colmap_camera_models.h)
};

// One keypoint of an image: its position in pixels (COLMAP's: the top-left corner of the
// image is (0, 0), so the first pixel's centre is (0.5, 0.5)) and the 3D point it observes.
// COLMAP's POINT3D_ID of a keypoint without a 3D point (written -1 in text form).
constexpr uint64_t kColmapNoPoint3D = ~uint64_t(0);
struct ColmapPoint2D {
  Vec2d xy;
  uint64_t point3DId = kColmapNoPoint3D;
};

// One image's pose. COLMAP stores world-to-camera: x_camera = R(qvec) x_world + tvec, with
// OpenCV camera axes (x right, y down, z forward).
struct ColmapImage {
  uint32_t id = 0;
  Quatd qvec;  // (w, x, y, z), Hamilton; kept as stored, its norm checked to be 1 within 1e-3
  Vec3d tvec;
  uint32_t cameraId = 0;
  std::string name;  // relative to the project's image folder
  std::vector<ColmapPoint2D> points2D;
};

// One observation of a 3D point: the image that saw it and which of its 2D points it is.
struct ColmapTrackElement {
  uint32_t imageId = 0;
  uint32_t point2DIndex = 0;
};

// One 3D point of points3D with its track: the images that observed it.
struct ColmapPoint {
  uint64_t id = 0;
  Vec3d xyz;
  std::array<uint8_t, 3> rgb{};
  double error = 0;  // mean reprojection error in pixels; COLMAP writes -1 when not computed
  std::vector<ColmapTrackElement> track;
};

enum class ColmapFormat { Text, Binary };

struct ColmapModel {
  std::vector<ColmapCamera> cameras;  // in file order
  std::vector<ColmapImage> images;
  std::vector<ColmapPoint> points;
  ColmapFormat format = ColmapFormat::Binary;  // which files were read
};

// The contents of a model's three files, in either form.
struct ColmapFiles {
  std::string cameras, images, points;
};

// Parses the three files of a model (text or binary); folderName is used for error
// messages only ("<folderName>/cameras.txt: line 4: ..."). Checks each file's syntax
// (binary: truncation, counts larger than the remaining bytes, trailing bytes), known
// camera models with the right number of parameters, finite numbers, image sizes in
// [1, 2^20], quaternion norms within 1e-3 of 1, unique camera, image and point ids and
// unique image names, and that every image's camera exists. Camera models are not
// checked for distortion here (see readColmapModel). Throws Error naming the file, the
// line (text) or record index and byte offset (binary), and the problem.
ColmapModel parseColmapModel(const ColmapFiles& files, ColmapFormat format, const std::string& folderName);

// Reads the model in folder: cameras.bin, images.bin and points3D.bin if cameras.bin
// exists (COLMAP's own preference), otherwise the .txt files. Beyond parseColmapModel it
// refuses cameras with lens distortion (colmapPinholeIntrinsics), naming the
// colmap image_undistorter command that fixes them. Throws Error naming the file.
ColmapModel readColmapModel(const std::filesystem::path& folder);
// The same without the distortion check: any camera model COLMAP defines (for glint
// capture, which reads COLMAP's own output before undistorting it).
ColmapModel readColmapModelAnyCamera(const std::filesystem::path& folder);

// The three files of a model in COLMAP's text form (with COLMAP's header comments, numbers
// at full round-trip precision) or binary form, 2D points and tracks as the model holds them.
ColmapFiles formatColmapModel(const ColmapModel& model, ColmapFormat format);
// Writes cameras, images and points3D (.txt or .bin) into folder, each atomically,
// creating the folder if needed.
void writeColmapModelText(const std::filesystem::path& folder, const ColmapModel& model);
void writeColmapModelBinary(const std::filesystem::path& folder, const ColmapModel& model);

}  // namespace glint
