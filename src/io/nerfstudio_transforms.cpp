// Strict parsing and writing of nerfstudio's transforms.json with nlohmann-json.
#include "io/nerfstudio_transforms.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "io/json_file.h"
#include "core/printable_text.h"
#include "io/colmap_records.h"

namespace glint {

namespace {

using Json = nlohmann::json;

// Pose tolerances as for transforms_{split}.json (io/transforms_json.cpp): the last row is
// written exactly, rotations printed with few digits drift from orthonormal by ~1e-6.
constexpr double kLastRowTolerance = 1e-4;
constexpr double kOrthonormalTolerance = 1e-3;
// Every lens distortion key nerfstudio (or COLMAP's FULL_OPENCV through it) may write.
constexpr const char* kDistortionKeys[] = {"k1", "k2", "k3", "k4", "k5", "k6", "p1", "p2"};
// Camera models whose projection is a pinhole's once the distortion keys are 0.
constexpr const char* kPinholeModels[] = {"OPENCV", "PINHOLE", "SIMPLE_PINHOLE"};


// Errors for one object: the file's top level (where = "") or frame i ("frame i: ").
struct Place {
  const std::string& fileName;
  std::string where;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw Error(fileName, where + key + " " + problem);
  }
};

double numberAt(const Json& value, const Place& place, const char* key) {
  if (!value.is_number()) place.fail(key, "must be a number");
  return value.get<double>();
}

double positiveAt(const Json& value, const Place& place, const char* key, const char* unit) {
  double v = numberAt(value, place, key);
  if (!(v > 0) || !std::isfinite(v)) {
    std::ostringstream s;
    s << "is " << v << ", but must be a positive number (" << unit << ")";
    place.fail(key, s.str());
  }
  return v;
}

int sizeAt(const Json& value, const Place& place, const char* key) {
  double v = numberAt(value, place, key);
  if (!(v >= 1 && v <= kMaxColmapImageSide) || v != std::floor(v)) {
    std::ostringstream s;
    s << "is " << v << ", but must be a whole number of pixels in [1, " << kMaxColmapImageSide << "]";
    place.fail(key, s.str());
  }
  return int(v);
}

// A path relative to the file's folder: "./" dropped, absolute paths and ".." refused.
std::string relativePathAt(const Json& value, const Place& place, const char* key) {
  if (!value.is_string()) place.fail(key, "must be a string");
  std::string path = value.get<std::string>();
  while (path.rfind("./", 0) == 0) path.erase(0, 2);
  if (path.empty()) place.fail(key, "is empty");
  if (path.front() == '/') place.fail(key, "\"" + printableText(path) + "\" must be relative to the file's folder");
  for (const auto& part : std::filesystem::path(path))
    if (part == "..")
      place.fail(key, "\"" + printableText(path) + "\" leaves the dataset folder (\"..\"); every file must lie inside it");
  return path;
}

// rows x 4 finite numbers; a 3x4 matrix gets the last row 0 0 0 1.
Mat4 matrixAt(const Json& value, const Place& place, const char* key, bool allowThreeRows) {
  const char* shape = allowThreeRows ? "must be 3 or 4 rows of 4 numbers" : "must be 4 rows of 4 numbers";
  if (!value.is_array() || !(value.size() == 4 || (allowThreeRows && value.size() == 3))) place.fail(key, shape);
  Mat4 matrix = Mat4::identity();
  for (size_t r = 0; r < value.size(); ++r) {
    const Json& row = value[r];
    if (!row.is_array() || row.size() != 4) place.fail(key, shape);
    for (size_t c = 0; c < 4; ++c) {
      if (!row[c].is_number()) place.fail(key, shape);
      matrix.m[r][c] = row[c].get<double>();
    }
  }
  const auto& m = matrix.m;
  if (std::abs(m[3][0]) > kLastRowTolerance || std::abs(m[3][1]) > kLastRowTolerance ||
      std::abs(m[3][2]) > kLastRowTolerance || std::abs(m[3][3] - 1.0) > kLastRowTolerance)
    place.fail(key, "must be affine: its last row must be 0 0 0 1");
  return matrix;
}

// Camera poses are rigid: R^T R = I (no scale or shear) and det R = +1 (no mirroring).
void checkRigid(const Mat4& matrix, const Place& place, const char* key) {
  const auto& m = matrix.m;
  double worst = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double d = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
      worst = std::max(worst, std::abs(d - (i == j ? 1.0 : 0.0)));
    }
  if (worst > kOrthonormalTolerance) {
    std::ostringstream s;
    s << "must be a rigid camera pose: its upper 3x3 is not a rotation (largest error of R^T R - I is " << worst
      << ", allowed " << kOrthonormalTolerance << ")";
    place.fail(key, s.str());
  }
  double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (det < 0) place.fail(key, "must be a rigid camera pose: its upper 3x3 is a reflection (determinant -1)");
}

// Refuses camera models and lens distortion that a pinhole cannot trace.
void checkPinhole(const Json& object, const Place& place) {
  auto model = object.find("camera_model");
  if (model != object.end()) {
    if (!model->is_string()) place.fail("camera_model", "must be a string");
    std::string name = model->get<std::string>();
    if (std::none_of(std::begin(kPinholeModels), std::end(kPinholeModels), [&](const char* m) { return name == m; }))
      place.fail("camera_model", "is \"" + printableText(name) +
                                     "\", but Glint traces pinhole cameras only (OPENCV, PINHOLE or "
                                     "SIMPLE_PINHOLE without distortion): undistort the images and write "
                                     "transforms.json for pinhole cameras (for COLMAP data, colmap "
                                     "image_undistorter --output_type COLMAP, then ns-process-data on its output)");
  }
  for (const char* key : kDistortionKeys) {
    auto value = object.find(key);
    if (value == object.end()) continue;
    double v = numberAt(*value, place, key);
    if (v != 0.0) {
      std::ostringstream s;
      s << "is " << v << ": the images have lens distortion, which Glint does not model. Undistort them and "
        << "write transforms.json with zero distortion (for COLMAP data: colmap image_undistorter "
        << "--output_type COLMAP, then ns-process-data on the undistorted model and images)";
      place.fail(key, s.str());
    }
  }
}

// The value of key in the frame if it has it, else in the file's top level, else null;
// place is set to where it was found, for messages.
const Json* lookup(const Json& frame, const Json& root, const char* key, const Place& framePlace,
                   const Place& rootPlace, const Place** place) {
  auto own = frame.find(key);
  if (own != frame.end()) {
    *place = &framePlace;
    return &*own;
  }
  auto global = root.find(key);
  if (global != root.end()) {
    *place = &rootPlace;
    return &*global;
  }
  return nullptr;
}

void resolveIntrinsics(const Json& frame, const Json& root, const Place& framePlace, const Place& rootPlace,
                       NerfstudioFrame* out) {
  const Place* place = nullptr;
  const Json* w = lookup(frame, root, "w", framePlace, rootPlace, &place);
  if (!w) framePlace.fail("w", "is missing (image width in pixels, in the frame or at the top level)");
  out->width = sizeAt(*w, *place, "w");
  const Json* h = lookup(frame, root, "h", framePlace, rootPlace, &place);
  if (!h) framePlace.fail("h", "is missing (image height in pixels, in the frame or at the top level)");
  out->height = sizeAt(*h, *place, "h");

  // Field-of-view fallbacks as in Blender-style files: f = size / (2 tan(angle / 2)).
  auto fromAngle = [](const Json& value, const Place& at, const char* key, int size) {
    double angle = numberAt(value, at, key);
    if (!(angle > 0 && angle < std::numbers::pi)) {
      std::ostringstream s;
      s << "is " << angle << ", but must lie in (0, pi) radians";
      at.fail(key, s.str());
    }
    return 0.5 * size / std::tan(0.5 * angle);
  };
  if (const Json* fx = lookup(frame, root, "fl_x", framePlace, rootPlace, &place))
    out->fx = positiveAt(*fx, *place, "fl_x", "focal length in pixels");
  else if (const Json* angle = lookup(frame, root, "camera_angle_x", framePlace, rootPlace, &place))
    out->fx = fromAngle(*angle, *place, "camera_angle_x", out->width);
  else
    framePlace.fail("fl_x", "is missing (focal length in pixels; camera_angle_x, the horizontal field of view in "
                            "radians, would do too)");
  if (const Json* fy = lookup(frame, root, "fl_y", framePlace, rootPlace, &place))
    out->fy = positiveAt(*fy, *place, "fl_y", "focal length in pixels");
  else if (const Json* angle = lookup(frame, root, "camera_angle_y", framePlace, rootPlace, &place))
    out->fy = fromAngle(*angle, *place, "camera_angle_y", out->height);
  else
    out->fy = out->fx;
  // The principal point defaults to the image centre.
  out->cx = 0.5 * out->width;
  out->cy = 0.5 * out->height;
  if (const Json* cx = lookup(frame, root, "cx", framePlace, rootPlace, &place)) out->cx = numberAt(*cx, *place, "cx");
  if (const Json* cy = lookup(frame, root, "cy", framePlace, rootPlace, &place)) out->cy = numberAt(*cy, *place, "cy");
}

std::string exact(double value) { return Json(value).dump(); }

void writeMatrixRows(std::ostringstream& out, const Mat4& m, int rows, const char* indent) {
  for (int r = 0; r < rows; ++r) {
    out << indent << "[";
    for (int c = 0; c < 4; ++c) out << (c ? ", " : "") << exact(m.m[r][c]);
    out << (r + 1 < rows ? "],\n" : "]\n");
  }
}

}  // namespace

NerfstudioTransforms parseNerfstudioTransforms(const std::string& text, const std::string& fileName) {
  Json root = parseJsonText(text, fileName);
  if (!root.is_object()) throw Error(fileName, "must hold a JSON object with frames");
  Place rootPlace{fileName, ""};
  checkPinhole(root, rootPlace);

  NerfstudioTransforms result;
  if (auto applied = root.find("applied_transform"); applied != root.end()) {
    result.appliedTransform = matrixAt(*applied, rootPlace, "applied_transform", true);
    const auto& m = result.appliedTransform.m;
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    // Points are mapped through it, and poses back through its inverse: it must have one.
    if (!(std::abs(det) > 1e-9)) rootPlace.fail("applied_transform", "must be invertible (its 3x3 part is singular)");
    result.hasAppliedTransform = true;
  }
  if (auto ply = root.find("ply_file_path"); ply != root.end())
    result.plyFilePath = relativePathAt(*ply, rootPlace, "ply_file_path");

  auto frames = root.find("frames");
  if (frames == root.end()) throw Error(fileName, "frames is missing");
  if (!frames->is_array()) throw Error(fileName, "frames must be an array");
  for (size_t i = 0; i < frames->size(); ++i) {
    const Json& frame = (*frames)[i];
    Place place{fileName, "frame " + std::to_string(i) + ": "};
    if (!frame.is_object()) throw Error(fileName, place.where + "must be an object with file_path and transform_matrix");
    checkPinhole(frame, place);
    NerfstudioFrame parsed;
    auto path = frame.find("file_path");
    if (path == frame.end()) place.fail("file_path", "is missing");
    parsed.filePath = relativePathAt(*path, place, "file_path");
    auto matrix = frame.find("transform_matrix");
    if (matrix == frame.end()) place.fail("transform_matrix", "is missing");
    parsed.transformMatrix = matrixAt(*matrix, place, "transform_matrix", false);
    checkRigid(parsed.transformMatrix, place, "transform_matrix");
    resolveIntrinsics(frame, root, place, rootPlace, &parsed);
    if (auto depth = frame.find("depth_file_path"); depth != frame.end())
      parsed.depthFilePath = relativePathAt(*depth, place, "depth_file_path");
    if (auto mask = frame.find("mask_path"); mask != frame.end())
      parsed.maskPath = relativePathAt(*mask, place, "mask_path");
    result.frames.push_back(std::move(parsed));
  }

  std::stable_sort(result.frames.begin(), result.frames.end(),
                   [](const NerfstudioFrame& a, const NerfstudioFrame& b) { return a.filePath < b.filePath; });
  for (size_t i = 1; i < result.frames.size(); ++i)
    if (result.frames[i].filePath == result.frames[i - 1].filePath)
      throw Error(fileName, "two frames have the same file_path \"" + printableText(result.frames[i].filePath) + "\"");
  return result;
}

NerfstudioTransforms readNerfstudioTransforms(const std::filesystem::path& path) {
  return parseNerfstudioTransforms(readInputFile(path, kMaxJsonFileBytes), path.string());
}

std::string formatNerfstudioTransforms(const NerfstudioTransforms& transforms) {
  // Our layout, so that each matrix row reads as one line; nlohmann's dump() gives
  // round-trip precision for doubles and escapes strings.
  std::ostringstream out;
  out << "{\n  \"camera_model\": \"PINHOLE\",\n";
  if (transforms.hasAppliedTransform) {
    out << "  \"applied_transform\": [\n";
    writeMatrixRows(out, transforms.appliedTransform, 3, "    ");
    out << "  ],\n";
  }
  if (!transforms.plyFilePath.empty()) out << "  \"ply_file_path\": " << Json(transforms.plyFilePath).dump() << ",\n";
  out << "  \"frames\": [";
  for (size_t i = 0; i < transforms.frames.size(); ++i) {
    const NerfstudioFrame& f = transforms.frames[i];
    out << (i ? ",\n" : "\n") << "    {\n      \"file_path\": " << Json(f.filePath).dump() << ",\n";
    out << "      \"w\": " << f.width << ", \"h\": " << f.height << ", \"fl_x\": " << exact(f.fx)
        << ", \"fl_y\": " << exact(f.fy) << ", \"cx\": " << exact(f.cx) << ", \"cy\": " << exact(f.cy) << ",\n";
    if (!f.depthFilePath.empty()) out << "      \"depth_file_path\": " << Json(f.depthFilePath).dump() << ",\n";
    if (!f.maskPath.empty()) out << "      \"mask_path\": " << Json(f.maskPath).dump() << ",\n";
    out << "      \"transform_matrix\": [\n";
    writeMatrixRows(out, f.transformMatrix, 4, "        ");
    out << "      ]\n    }";
  }
  out << (transforms.frames.empty() ? "]\n}\n" : "\n  ]\n}\n");
  return out.str();
}

void writeNerfstudioTransforms(const std::filesystem::path& path, const NerfstudioTransforms& transforms) {
  writeTextAtomically(path, formatNerfstudioTransforms(transforms));
}

}  // namespace glint
