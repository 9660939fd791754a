// Point clouds as PLY vertex tables: x y z float, red green blue uchar.
#include "io/point_cloud.h"

#include <string>

#include "core/error.h"
#include "io/ply.h"

namespace glint {

namespace fs = std::filesystem;

void writePointCloud(const fs::path& path, const PointCloud& cloud) {
  GLINT_CHECK(cloud.colors.empty() || cloud.colors.size() == cloud.positions.size(),
              "point cloud needs one colour per point, or none");
  size_t n = cloud.positions.size();
  PlyTable table;
  table.count = n;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<float> values(n);
    for (size_t i = 0; i < n; ++i) values[i] = cloud.positions[i][axis];
    table.add(std::string(1, "xyz"[axis]), std::move(values));
  }
  if (!cloud.colors.empty()) {
    static const char* const kColorNames[] = {"red", "green", "blue"};
    for (int channel = 0; channel < 3; ++channel) {
      // writePly rounds and clamps to 0..255.
      std::vector<float> values(n);
      for (size_t i = 0; i < n; ++i) values[i] = cloud.colors[i][channel] * 255.0f;
      table.add(kColorNames[channel], std::move(values), PlyType::UInt8);
    }
  }
  writePly(path, table);
}

PointCloud readPointCloud(const fs::path& path) {
  PlyTable table = readPly(path, "vertex");
  PointCloud cloud;
  const std::vector<float>& x = table.column("x");
  const std::vector<float>& y = table.column("y");
  const std::vector<float>& z = table.column("z");
  cloud.positions.resize(table.count);
  for (size_t i = 0; i < table.count; ++i) cloud.positions[i] = Vec3f(x[i], y[i], z[i]);

  static const char* const kColorNames[] = {"red", "green", "blue"};
  int colourChannels = int(table.has("red")) + int(table.has("green")) + int(table.has("blue"));
  if (colourChannels == 0) return cloud;
  if (colourChannels != 3) throw Error(path.string(), "PLY vertex colour needs all of red, green and blue");
  cloud.colors.resize(table.count);
  for (int channel = 0; channel < 3; ++channel) {
    const char* name = kColorNames[channel];
    // Integer colours are fractions of their type's maximum; float colours are already in [0, 1].
    float scale = 1.0f;
    switch (table.type(name)) {
      case PlyType::UInt8: scale = 1.0f / 255.0f; break;
      case PlyType::UInt16: scale = 1.0f / 65535.0f; break;
      case PlyType::Float32: case PlyType::Float64: break;
      default:
        throw Error(path.string(), std::string("unsupported type '") + plyTypeName(table.type(name)) +
                                       "' for vertex colour '" + name + "' (expected uchar, ushort or float)");
    }
    const std::vector<float>& values = table.column(name);
    for (size_t i = 0; i < table.count; ++i) cloud.colors[i][channel] = values[i] * scale;
  }
  return cloud;
}

}  // namespace glint
