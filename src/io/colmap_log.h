// Reading what COLMAP's command-line tools print: progress while they run, and the
// statistics of a model (colmap model_analyzer).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace glint {

// How far a COLMAP step is, from one line of its output.
struct ColmapProgress {
  long done = 0;
  long total = 0;  // 0 when the line does not say (the mapper's count of registered images)
};

// The progress a line reports, or nullopt for any other line. Understood (COLMAP 3.8):
//   feature_extractor   "Processed file [3/24]"
//   exhaustive_matcher  "Matching block [2/3, 1/3]"  (block i of B, j of B: (i-1)*B + j of B*B)
//   sequential_matcher  "Matching image [5/120]"
//   mapper              "Registering image #17 (9)"  (9 images registered so far, total 0)
//   image_undistorter   "Undistorting image [4/24]"
std::optional<ColmapProgress> parseColmapProgress(std::string_view line);

// The figures colmap model_analyzer prints (on its log lines, "I... ] Points: 988").
struct ColmapModelStats {
  long cameras = 0;
  long images = 0;
  long registeredImages = 0;
  long points = 0;
  long observations = 0;
  double meanTrackLength = 0;
  double meanReprojectionError = 0;  // pixels
};

// Reads model_analyzer's output; nullopt when "Registered images" or "Mean reprojection
// error" is missing (an older or newer COLMAP that words them differently).
std::optional<ColmapModelStats> parseColmapModelStats(std::string_view output);

}  // namespace glint
