// Coloured point clouds in binary PLY (x y z float, red green blue uchar), as used by
// point_cloud_dense.ply for initialisation.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "math/vec.h"

namespace glint {

struct PointCloud {
  std::vector<Vec3f> positions;
  std::vector<Rgb> colors;  // in [0, 1]; either one per position or empty (no colour)
};

// Writes binary little-endian PLY atomically (red green blue only if colors is non-empty).
void writePointCloud(const std::filesystem::path& path, const PointCloud& cloud);
// Reads a PLY point cloud (binary little-endian; properties by name, unknown ones
// ignored; colour optional: uchar / ushort scaled to [0, 1], float used as is; colors is
// left empty if the file has none). Throws Error naming the file.
PointCloud readPointCloud(const std::filesystem::path& path);

}  // namespace glint
