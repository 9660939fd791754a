// The text form of a COLMAP model: cameras.txt, images.txt, points3D.txt.
#pragma once

#include <string>
#include <vector>

#include "io/colmap_model.h"

namespace glint {

// Each parser checks syntax and single records (io/colmap_records.h) and that ids (and
// image names) are unique; fileName is for messages ("<fileName>: line N: ...").
std::vector<ColmapCamera> parseColmapCamerasText(const std::string& text, const std::string& fileName);
// Two lines per image; the second (2D points as X Y POINT3D_ID triples) is always the
// line right after the first and may be empty; a file may end without it.
std::vector<ColmapImage> parseColmapImagesText(const std::string& text, const std::string& fileName);
// TRACK[] (IMAGE_ID POINT2D_IDX pairs) is checked and skipped.
std::vector<ColmapPoint> parseColmapPointsText(const std::string& text, const std::string& fileName);

// The 1-based line number of each record of cameras.txt or points3D.txt (the lines that
// are neither blank nor comments), for messages about records found after parsing.
std::vector<int> colmapTextRecordLines(const std::string& text);

// COLMAP's text layout with its header comments; numbers at shortest round-trip precision.
std::string formatColmapCamerasText(const std::vector<ColmapCamera>& cameras);
std::string formatColmapImagesText(const std::vector<ColmapImage>& images);
std::string formatColmapPointsText(const std::vector<ColmapPoint>& points);

}  // namespace glint
