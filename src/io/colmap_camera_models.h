// COLMAP's camera models (ids, names, parameter counts) and which of them Glint accepts:
// only distortion-free pinhole cameras, with the undistortion command for the others.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct ColmapCamera;

// One entry of COLMAP's fixed table of camera models (docs/capture-format.md).
struct ColmapCameraModel {
  int id;              // the model_id stored in cameras.bin
  const char* name;    // the MODEL name written in cameras.txt
  int numParams;       // length of PARAMS[]
  // Index of the first distortion parameter; numParams when the model has none.
  int firstDistortionParam;
  // True when the projection with every distortion parameter exactly 0 is a pinhole
  // projection (the perspective models); false for the fisheye and FOV models, whose
  // projections differ from a pinhole's even when their coefficients are 0.
  bool perspectiveWhenUndistorted;
};

// The model with this id or name, or nullptr for one COLMAP does not define.
const ColmapCameraModel* findColmapCameraModel(int id);
const ColmapCameraModel* findColmapCameraModel(const std::string& name);

// Pinhole intrinsics in pixels; the principal point is measured from the image's top-left
// corner, so the centre of pixel (i, j) is (i + 0.5, j + 0.5) (COLMAP's convention).
struct PinholeIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

// True unless the camera projects like a pinhole: a fisheye or FOV model, a perspective
// model with a distortion parameter other than 0, or a model COLMAP does not define.
bool hasLensDistortion(const ColmapCamera& camera);

// fx, fy, cx, cy of a camera that projects like a pinhole: PINHOLE, SIMPLE_PINHOLE, or a
// perspective distortion model (SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV) whose
// distortion parameters are all exactly 0. Any other camera throws Error naming
// `where` (file and record), the model and its distortion, with the colmap
// image_undistorter command that removes it (undistortionCommand(modelFolder)). Also
// throws if a focal length is not positive.
PinholeIntrinsics colmapPinholeIntrinsics(const ColmapCamera& camera, const std::string& fileName,
                                          const std::string& where, const std::filesystem::path& modelFolder = {});

// The command that writes an undistorted copy of a model and its images, with the paths
// filled in where they can be guessed: a model in <project>/sparse or <project>/sparse/N
// whose <project>/images exists gives --image_path <project>/images and --output_path
// <project>/undistorted; unknown paths are left as <images folder> and <new folder>.
std::string undistortionCommand(const std::filesystem::path& modelFolder);

}  // namespace glint
