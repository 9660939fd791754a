// The binary form of a COLMAP model: cameras.bin, images.bin, points3D.bin (little-endian).
#pragma once

#include <string>
#include <vector>

#include "io/colmap_model.h"

namespace glint {

// Each parser checks that every count fits in the bytes left before anything is sized
// from it, that no record is cut short and nothing follows the last one, the single
// records (io/colmap_records.h), and that ids (and image names) are unique. fileName is
// for messages ("<fileName>: record N at byte B: ...").
std::vector<ColmapCamera> parseColmapCamerasBinary(const std::string& bytes, const std::string& fileName);
// Each image with its 2D points.
std::vector<ColmapImage> parseColmapImagesBinary(const std::string& bytes, const std::string& fileName);
// Each point with its track.
std::vector<ColmapPoint> parseColmapPointsBinary(const std::string& bytes, const std::string& fileName);

// COLMAP's binary layout, with the 2D points and tracks the model holds.
std::string formatColmapCamerasBinary(const std::vector<ColmapCamera>& cameras);
std::string formatColmapImagesBinary(const std::vector<ColmapImage>& images);
std::string formatColmapPointsBinary(const std::vector<ColmapPoint>& points);

}  // namespace glint
