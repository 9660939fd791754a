// Writes a small dataset in the NeRF-synthetic Blender layout, as the tests need one:
// transforms_{split}.json with file_path "./SPLIT/r_N" (no extension) and 8-bit sRGB RGBA
// PNGs, made here rather than committed as binaries.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "io/image.h"
#include "math/mat4.h"

namespace glint::test {

constexpr double kNerfCameraAngleX = 0.6911112070083618;  // the value of the lego scene's files
constexpr double kNerfCameraDistance = 4.0;

// The pose of view i of n: on a circle of radius 4 around the origin, 1 unit up, looking
// at the origin (Blender's camera axes, which are OpenGL's: x right, y up, looking down -z).
inline Mat4 nerfCameraPose(int i, int n) {
  const double angle = 2.0 * 3.14159265358979323846 * (i + 0.25) / n;
  const Vec3d eye(kNerfCameraDistance * std::cos(angle), kNerfCameraDistance * std::sin(angle), 1.0);
  return Mat4::lookAt(eye, Vec3d(0.0), Vec3d(0, 0, 1));  // z up, as Blender's world
}

// The 8-bit codes of pixel (x, y) of view `seed`: the left half opaque, the right half
// transparent, and column 1 half covered (alpha 128), so that compositing shows.
inline Image nerfImage(int width, int height, int seed) {
  Image image(width, height, 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float codes[4] = {float((40 + 20 * seed + 7 * x) % 256), float((200 + 3 * y) % 256), 90.0f,
                              x < width / 2 ? (x == 1 ? 128.0f : 255.0f) : 0.0f};
      for (int c = 0; c < 4; ++c) image.at(x, y, c) = codes[c] / 255.0f;
    }
  return image;
}

// Writes transforms_<split>.json and <split>/r_<i>.png for each split named with its view
// count (e.g. {{"train", 4}, {"val", 2}}).
inline void writeNerfSyntheticDataset(const std::filesystem::path& root,
                                      const std::vector<std::pair<std::string, int>>& splits, int width = 16,
                                      int height = 12) {
  std::filesystem::create_directories(root);
  int seed = 0;
  for (const auto& [split, count] : splits) {
    std::filesystem::create_directories(root / split);
    nlohmann::json frames = nlohmann::json::array();
    for (int i = 0; i < count; ++i) {
      const Mat4 pose = nerfCameraPose(seed, 8);
      nlohmann::json rows = nlohmann::json::array();
      for (int r = 0; r < 4; ++r) rows.push_back({pose.m[r][0], pose.m[r][1], pose.m[r][2], pose.m[r][3]});
      frames.push_back({{"file_path", "./" + split + "/r_" + std::to_string(i)}, {"rotation", 0.012566370614359171},
                        {"transform_matrix", rows}});
      writeImage(root / split / ("r_" + std::to_string(i) + ".png"), nerfImage(width, height, seed++));
    }
    writeTextAtomically(root / ("transforms_" + split + ".json"),
                        nlohmann::json{{"camera_angle_x", kNerfCameraAngleX}, {"frames", frames}}.dump(4));
  }
}

}  // namespace glint::test
