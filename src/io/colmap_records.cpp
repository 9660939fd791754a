// Record checks shared by the COLMAP text and binary parsers.
#include "io/colmap_records.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string_view>
#include <utility>

#include "core/printable_text.h"
#include "io/colmap_camera_models.h"

namespace glint {

std::string colmapImageNameProblem(const std::string& name) {
  if (name.empty()) return "the image name is empty";
  for (unsigned char c : name)
    if (c < 0x20 || c == 0x7f) return "the image name \"" + printableText(name) + "\" has a control character";
  if (name.front() == ' ' || name.back() == ' ')
    return "the image name \"" + printableText(name) + "\" starts or ends with a space";
  // Names are joined to the image folder: like a dataset's file_path they must stay inside it.
  if (name.front() == '/') return "the image name \"" + printableText(name) + "\" is an absolute path";
  for (const auto& part : std::filesystem::path(name))
    if (part == "..")
      return "the image name \"" + printableText(name) + "\" leaves the image folder (\"..\")";
  return "";
}

namespace {

// A decimal side in [1, kMaxColmapImageSide]: digits only, no sign, at most 7 of them.
bool plausibleSide(std::string_view side) {
  if (side.empty() || side.size() > 7 || side.find_first_not_of("0123456789") != std::string_view::npos) return false;
  const long value = std::stol(std::string(side));
  return value >= 1 && value <= kMaxColmapImageSide;
}

bool decimalInteger(std::string_view text) {
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) text.remove_prefix(1);
  return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
}

}  // namespace

std::string colmapImageSizeProblem(std::string_view width, std::string_view height) {
  for (const auto& [name, side] : {std::pair{"WIDTH", width}, std::pair{"HEIGHT", height}})
    if (!decimalInteger(side)) return std::string(name) + " \"" + printableText(side) + "\" is not an integer";
  if (plausibleSide(width) && plausibleSide(height)) return "";
  return "image size " + printableText(width) + " x " + printableText(height) + " is not in [1, " +
         std::to_string(kMaxColmapImageSide) + "] pixels";
}

std::string colmapCameraProblem(const ColmapCamera& camera) {
  const ColmapCameraModel* model = findColmapCameraModel(camera.model);
  if (!model) return "unknown camera model \"" + printableText(camera.model) + "\"";
  if (int(camera.params.size()) != model->numParams)
    return "camera model " + camera.model + " takes " + std::to_string(model->numParams) + " parameters, but " +
           std::to_string(camera.params.size()) + " are given";
  if (camera.width < 1 || camera.width > kMaxColmapImageSide || camera.height < 1 ||
      camera.height > kMaxColmapImageSide)
    return "image size " + std::to_string(camera.width) + " x " + std::to_string(camera.height) +
           " is not in [1, " + std::to_string(kMaxColmapImageSide) + "] pixels";
  for (size_t i = 0; i < camera.params.size(); ++i)
    if (!std::isfinite(camera.params[i])) return "parameter " + std::to_string(i) + " is not a finite number";
  return "";
}

std::string colmapImageProblem(const ColmapImage& image) {
  const Quatd& q = image.qvec;
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
    return "the quaternion is not finite";
  if (!isFinite(image.tvec)) return "the translation is not finite";
  double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= kColmapQuaternionTolerance)) {
    std::ostringstream s;
    s << "the quaternion (" << q.w << ", " << q.x << ", " << q.y << ", " << q.z << ") has norm " << norm
      << ", but a rotation's is 1 (allowed error " << kColmapQuaternionTolerance << ")";
    return s.str();
  }
  return colmapImageNameProblem(image.name);
}

std::string colmapPointProblem(const ColmapPoint& point) {
  if (!isFinite(point.xyz)) return "the position is not finite";
  if (!std::isfinite(point.error)) return "the reprojection error is not finite";
  return "";
}

}  // namespace glint
