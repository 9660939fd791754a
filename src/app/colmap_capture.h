// From a folder of photographs to a capture Glint trains on, through Debian's COLMAP:
// features, matching, mapping, the largest model, undistortion (glint capture).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct CaptureRequest {
  std::filesystem::path photos;  // a folder of JPEG/PNG photos, or a folder holding images/
  std::filesystem::path output;  // the capture folder to write
  // A COLMAP camera model (PINHOLE, SIMPLE_RADIAL, OPENCV, ...) or "auto": OPENCV, as
  // INRIA's convert.py and nerfstudio use, unless the photos come with priors/, whose
  // pixels must stay aligned with the photographs (then PINHOLE).
  std::string cameraModel = "auto";
  bool cameraPerImage = false;          // one camera per photograph instead of one shared
  std::string matcher = "exhaustive";  // or "sequential" (video frames in order)
  bool useKnownIntrinsics = true;      // start from PHOTOS/sparse/0's pinhole camera if there is one
  bool force = false;                   // replace an OUTPUT that glint capture wrote before
  int threads = 0;                      // 0 = all cores
  std::string colmap = "colmap";        // the program (a name on PATH or a path)
};

struct CaptureResult {
  int photographs = 0;  // given to COLMAP
  int registered = 0;   // in the model kept
  int models = 0;       // COLMAP's models (sparse/0, sparse/1, ...)
  long points = 0;
  double meanTrackLength = 0;
  double meanReprojectionError = 0;  // pixels
  std::string cameraModel;           // the model COLMAP estimated
  bool undistorted = false;          // images/ and sparse/0 are image_undistorter's
  bool priorsKept = false;
  std::vector<std::string> unregistered;  // photographs left out of the model
  double seconds = 0;
};

// Runs COLMAP over request.photos and writes request.output:
//   images/      the photographs (hard links), or their undistorted copies
//   priors/      PHOTOS/priors when the photographs were not resampled (hard links)
//   capture.json PHOTOS/capture.json when there is one
//   sparse/0/    the largest model, in COLMAP's binary form (pinhole cameras)
//   colmap/      COLMAP's database, every model it made, and its log (log.txt)
// The work happens in a hidden folder beside OUTPUT that replaces it only at the end, so a
// failed or interrupted run leaves OUTPUT as it was. Prints progress as COLMAP works.
// Throws Error for bad input (no photographs, OUTPUT that is not glint capture's, COLMAP
// missing) and when a COLMAP step fails (with the end of its output).
CaptureResult reconstructCapture(const CaptureRequest& request);

// The line that tells a user without COLMAP how to get it.
std::string colmapInstallAdvice();

}  // namespace glint
