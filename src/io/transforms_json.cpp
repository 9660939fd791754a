// Strict parsing and pretty-printing of transforms_{split}.json with nlohmann-json.
#include "io/transforms_json.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "io/json_file.h"
#include "core/printable_text.h"

namespace glint {

namespace {

using Json = nlohmann::json;

// Tolerances of the pose checks: the last row is written exactly by every tool we know,
// while rotations stored as text with 6-8 digits drift from orthonormal by ~1e-6.
constexpr double kLastRowTolerance = 1e-4;
constexpr double kOrthonormalTolerance = 1e-3;
// Fields of view narrower than 0.01 degrees (a 1000 mm lens on a 35 mm sensor still sees
// 2 degrees) put every pixel's ray within float precision of the next: the renders are
// black or one colour, so such a value is a unit mistake, not a camera.
constexpr double kMinFieldOfView = 0.01 * std::numbers::pi / 180.0;

bool endsWithNoCase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == std::tolower((unsigned char)b); });
}

std::string normalizeFilePath(std::string path) {
  while (path.rfind("./", 0) == 0) path.erase(0, 2);
  for (const char* ext : {".png", ".exr", ".tiff", ".tif"})
    if (endsWithNoCase(path, ext)) {
      path.resize(path.size() - std::string(ext).size());
      break;
    }
  return path;
}


Mat4 parseMatrix(const Json& value, const std::string& fileName, const std::string& where) {
  auto fail = [&](const std::string& problem) { throw Error(fileName, where + "transform_matrix " + problem); };
  if (!value.is_array() || value.size() != 4) fail("must be 4 rows of 4 numbers");
  Mat4 matrix;
  for (int r = 0; r < 4; ++r) {
    const Json& row = value[r];
    if (!row.is_array() || row.size() != 4) fail("must be 4 rows of 4 numbers");
    for (int c = 0; c < 4; ++c) {
      if (!row[c].is_number()) fail("must be 4 rows of 4 numbers");
      double v = row[c].get<double>();
      if (!std::isfinite(v))
        fail("row " + std::to_string(r) + " column " + std::to_string(c) + " is not a finite number");
      matrix.m[r][c] = v;
    }
  }
  const auto& m = matrix.m;
  if (std::abs(m[3][0]) > kLastRowTolerance || std::abs(m[3][1]) > kLastRowTolerance ||
      std::abs(m[3][2]) > kLastRowTolerance || std::abs(m[3][3] - 1.0) > kLastRowTolerance)
    fail("must be affine: its last row must be 0 0 0 1");
  // Rigid camera poses only: R^T R = I (no scale or shear) and det R = +1 (no mirroring).
  double worst = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double d = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
      worst = std::max(worst, std::abs(d - (i == j ? 1.0 : 0.0)));
    }
  if (worst > kOrthonormalTolerance) {
    std::ostringstream s;
    s << "must be a rigid camera pose: its upper 3x3 is not a rotation (columns not orthonormal, "
      << "largest error of R^T R - I is " << worst << ", allowed " << kOrthonormalTolerance
      << "; scaled or sheared cameras are not supported)";
    fail(s.str());
  }
  double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (det < 0) fail("must be a rigid camera pose: its upper 3x3 is a reflection (determinant -1), not a rotation");
  return matrix;
}

}  // namespace

TransformsFile parseTransformsJson(const std::string& text, const std::string& fileName) {
  Json root = parseJsonText(text, fileName);
  if (!root.is_object()) throw Error(fileName, "must hold a JSON object with camera_angle_x and frames");

  TransformsFile result;
  auto angle = root.find("camera_angle_x");
  if (angle == root.end()) throw Error(fileName, "camera_angle_x is missing (horizontal field of view in radians)");
  if (!angle->is_number()) throw Error(fileName, "camera_angle_x must be a number (radians)");
  result.cameraAngleX = angle->get<double>();
  if (!(result.cameraAngleX >= kMinFieldOfView && result.cameraAngleX < std::numbers::pi)) {
    std::ostringstream s;
    s << "camera_angle_x is " << result.cameraAngleX
      << ", but must lie in [0.000175, pi) radians (0.01 to 180 degrees; it is in radians, not degrees)";
    throw Error(fileName, s.str());
  }

  auto frames = root.find("frames");
  if (frames == root.end()) throw Error(fileName, "frames is missing");
  if (!frames->is_array()) throw Error(fileName, "frames must be an array");
  for (size_t i = 0; i < frames->size(); ++i) {
    const Json& frame = (*frames)[i];
    std::string where = "frame " + std::to_string(i) + ": ";
    if (!frame.is_object()) throw Error(fileName, where + "must be an object with file_path and transform_matrix");
    auto path = frame.find("file_path");
    if (path == frame.end()) throw Error(fileName, where + "file_path is missing");
    if (!path->is_string()) throw Error(fileName, where + "file_path must be a string");
    TransformsFrame parsed;
    parsed.filePath = normalizeFilePath(path->get<std::string>());
    if (parsed.filePath.empty()) throw Error(fileName, where + "file_path is empty");
    if (parsed.filePath.front() == '/')
      throw Error(fileName,
                  where + "file_path \"" + printableText(parsed.filePath) + "\" must be relative to the dataset folder");
    // A dataset is one folder: its files never lie outside it, so ".." is refused outright
    // (a downloaded dataset must not make Glint read, or synth write, elsewhere).
    for (const auto& part : std::filesystem::path(parsed.filePath))
      if (part == "..")
        throw Error(fileName, where + "file_path \"" + printableText(parsed.filePath) +
                                  "\" leaves the dataset folder (\"..\"); every file must lie inside it");
    auto matrix = frame.find("transform_matrix");
    if (matrix == frame.end()) throw Error(fileName, where + "transform_matrix is missing");
    parsed.transformMatrix = parseMatrix(*matrix, fileName, where);
    result.frames.push_back(std::move(parsed));
  }

  std::stable_sort(result.frames.begin(), result.frames.end(),
                   [](const TransformsFrame& a, const TransformsFrame& b) { return a.filePath < b.filePath; });
  for (size_t i = 1; i < result.frames.size(); ++i)
    if (result.frames[i].filePath == result.frames[i - 1].filePath)
      throw Error(fileName, "two frames have the same file_path \"" + printableText(result.frames[i].filePath) + "\"");
  return result;
}

TransformsFile readTransformsJson(const std::filesystem::path& path) {
  return parseTransformsJson(readInputFile(path, kMaxJsonFileBytes), path.string());
}

std::string formatTransformsJson(const TransformsFile& transforms) {
  // nlohmann's dump() prints doubles with round-trip precision and escapes strings; the
  // layout is ours so that each matrix row reads as one line.
  std::ostringstream out;
  out << "{\n  \"camera_angle_x\": " << Json(transforms.cameraAngleX).dump() << ",\n  \"frames\": [";
  for (size_t i = 0; i < transforms.frames.size(); ++i) {
    const TransformsFrame& frame = transforms.frames[i];
    out << (i ? ",\n" : "\n") << "    {\n      \"file_path\": " << Json(frame.filePath).dump()
        << ",\n      \"transform_matrix\": [\n";
    for (int r = 0; r < 4; ++r) {
      out << "        [";
      for (int c = 0; c < 4; ++c) out << (c ? ", " : "") << Json(frame.transformMatrix.m[r][c]).dump();
      out << (r < 3 ? "],\n" : "]\n");
    }
    out << "      ]\n    }";
  }
  out << (transforms.frames.empty() ? "]\n}\n" : "\n  ]\n}\n");
  return out.str();
}

void writeTransformsJson(const std::filesystem::path& path, const TransformsFile& transforms) {
  writeTextAtomically(path, formatTransformsJson(transforms));
}

}  // namespace glint
