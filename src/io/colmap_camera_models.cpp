// COLMAP's camera model table, and the refusal of lens distortion with the fix.
#include "io/colmap_camera_models.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "io/colmap_model.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// COLMAP's model ids are fixed by its file format (src/colmap/sensor/models.h); the
// parameters are the focal length(s) and principal point first, distortion after.
constexpr ColmapCameraModel kModels[] = {
    {0, "SIMPLE_PINHOLE", 3, 3, true},          // f, cx, cy
    {1, "PINHOLE", 4, 4, true},                 // fx, fy, cx, cy
    {2, "SIMPLE_RADIAL", 4, 3, true},           // f, cx, cy, k
    {3, "RADIAL", 5, 3, true},                  // f, cx, cy, k1, k2
    {4, "OPENCV", 8, 4, true},                  // fx, fy, cx, cy, k1, k2, p1, p2
    {5, "OPENCV_FISHEYE", 8, 4, false},         // fx, fy, cx, cy, k1, k2, k3, k4
    {6, "FULL_OPENCV", 12, 4, true},            // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
    {7, "FOV", 5, 4, false},                    // fx, fy, cx, cy, omega
    {8, "SIMPLE_RADIAL_FISHEYE", 4, 3, false},  // f, cx, cy, k
    {9, "RADIAL_FISHEYE", 5, 3, false},         // f, cx, cy, k1, k2
    {10, "THIN_PRISM_FISHEYE", 12, 4, false},   // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1
};

std::string distortionText(const ColmapCamera& camera, const ColmapCameraModel& model) {
  std::ostringstream s;
  s.precision(6);
  for (int i = model.firstDistortionParam; i < model.numParams; ++i)
    s << (i > model.firstDistortionParam ? ", " : "") << camera.params[size_t(i)];
  return s.str();
}

}  // namespace

const ColmapCameraModel* findColmapCameraModel(int id) {
  for (const ColmapCameraModel& model : kModels)
    if (model.id == id) return &model;
  return nullptr;
}

const ColmapCameraModel* findColmapCameraModel(const std::string& name) {
  for (const ColmapCameraModel& model : kModels)
    if (name == model.name) return &model;
  return nullptr;
}

std::string undistortionCommand(const fs::path& modelFolder) {
  std::string images = "<images folder>", output = "<new folder>", input = "<model folder>";
  if (!modelFolder.empty()) {
    fs::path model = modelFolder.lexically_normal();
    if (!model.has_filename()) model = model.parent_path();  // a trailing slash
    input = model.string();
    // COLMAP's project layout: <project>/images beside <project>/sparse/0 (or sparse).
    fs::path project = model.parent_path();
    if (project.filename() == "sparse") project = project.parent_path();
    std::error_code ignored;
    if (fs::is_directory(project / "images", ignored)) {
      images = (project / "images").string();
      output = (project / "undistorted").string();
    }
  }
  return "colmap image_undistorter --image_path " + images + " --input_path " + input + " --output_path " + output +
         " --output_type COLMAP";
}

bool hasLensDistortion(const ColmapCamera& camera) {
  const ColmapCameraModel* model = findColmapCameraModel(camera.model);
  if (!model || int(camera.params.size()) != model->numParams) return true;
  bool distorted = !model->perspectiveWhenUndistorted;
  for (int i = model->firstDistortionParam; i < model->numParams; ++i)
    if (camera.params[size_t(i)] != 0.0) distorted = true;
  return distorted;
}

PinholeIntrinsics colmapPinholeIntrinsics(const ColmapCamera& camera, const std::string& fileName,
                                          const std::string& where, const fs::path& modelFolder) {
  const ColmapCameraModel* model = findColmapCameraModel(camera.model);
  if (!model || int(camera.params.size()) != model->numParams)
    throw Error(fileName, where + "camera " + std::to_string(camera.id) + " has an unknown model or the wrong " +
                              "number of parameters");
  if (hasLensDistortion(camera)) {
    std::string what = model->perspectiveWhenUndistorted ? "lens distortion (" + distortionText(camera, *model) + ")"
                                                         : "a fisheye or FOV projection";
    throw Error(fileName, where + "camera " + std::to_string(camera.id) + " uses the " + camera.model +
                              " model with " + what +
                              ", but Glint traces pinhole cameras only. Undistort the images and the model "
                              "with\n  " +
                              undistortionCommand(modelFolder) +
                              "\nand use the images and sparse model it writes in the output folder.");
  }
  const std::vector<double>& p = camera.params;
  // One focal length (SIMPLE_*, RADIAL) or two (PINHOLE, OPENCV, ...), then cx, cy.
  bool oneFocal = model->firstDistortionParam == 3;
  PinholeIntrinsics k;
  k.fx = p[0];
  k.fy = oneFocal ? p[0] : p[1];
  k.cx = oneFocal ? p[1] : p[2];
  k.cy = oneFocal ? p[2] : p[3];
  if (!(k.fx > 0 && k.fy > 0 && std::isfinite(k.fx) && std::isfinite(k.fy)))
    throw Error(fileName, where + "camera " + std::to_string(camera.id) + " has a focal length that is not a " +
                              "positive number of pixels");
  if (!std::isfinite(k.cx) || !std::isfinite(k.cy))
    throw Error(fileName, where + "camera " + std::to_string(camera.id) + " has a non-finite principal point");
  return k;
}

}  // namespace glint
