// `glint capture PHOTOS -o CAPTURE`: cameras for a folder of photographs through COLMAP,
// written as a capture that glint train reads.
#include <cstdio>
#include <memory>

#include "app/colmap_capture.h"
#include "app/commands.h"
#include "app/thread_flag.h"
#include "core/progress.h"

namespace glint {

namespace {

void printSummary(const CaptureRequest& request, const CaptureResult& result) {
  std::printf("glint capture: registered %d of %d photographs (%d model%s made, the largest kept): %ld points, "
              "mean track length %.2f, mean reprojection error %.2f px, in %s\n",
              result.registered, result.photographs, result.models, result.models == 1 ? "" : "s", result.points,
              result.meanTrackLength, result.meanReprojectionError, formatDuration(result.seconds).c_str());
  if (!result.unregistered.empty()) {
    std::string names;
    for (size_t i = 0; i < result.unregistered.size() && i < 5; ++i) names += (i ? ", " : "") + result.unregistered[i];
    if (result.unregistered.size() > 5) names += ", ...";
    std::printf("glint capture: warning: %zu photograph(s) have no camera and are left out of training: %s\n",
                result.unregistered.size(), names.c_str());
  }
  std::printf("glint capture: cameras: %s%s\n", result.cameraModel.c_str(),
              result.undistorted ? ", undistorted to pinholes (images/ holds the undistorted photographs)" : "");
  std::string out = request.output.string();
  std::printf("glint capture: wrote %s (images/, %ssparse/0 in COLMAP's binary form, colmap/ with its database "
              "and log)\n",
              out.c_str(), result.priorsKept ? "priors/, " : "");
  std::printf("next:\n  glint info %s\n  glint train %s -o %s-run\n",
              out.c_str(), out.c_str(), out.c_str());
}

}  // namespace

void addCaptureCommand(CLI::App& app) {
  auto request = std::make_shared<CaptureRequest>();
  auto noIntrinsics = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "capture",
      "Get the cameras of a folder of photographs with COLMAP (features, matching, mapping, undistortion) and write "
      "a capture folder that glint train reads. Needs Debian's colmap (apt-get install colmap).");
  cmd->add_option("photos", request->photos,
                  "Folder of JPEG or PNG photographs of one scene, or a folder holding them in images/ (with "
                  "priors/ and capture.json, as glint synth --layout capture writes)")
      ->required();
  cmd->add_option("-o,--output", request->output,
                  "Capture folder to write: images/, sparse/0 (COLMAP's cameras), priors/ and capture.json when "
                  "PHOTOS has them, colmap/ (database and log)")
      ->required();
  cmd->add_option("--camera-model", request->cameraModel,
                  "COLMAP camera model to estimate (PINHOLE, SIMPLE_RADIAL, OPENCV, ...). auto: OPENCV, then "
                  "undistorted to pinholes, unless PHOTOS has priors/ (no distortion, so the priors stay aligned: "
                  "SIMPLE_PINHOLE, or PINHOLE when sparse/0's pixels are not square)")
      ->default_val("auto");
  cmd->add_flag("--camera-per-image", request->cameraPerImage,
                "Estimate intrinsics per photograph (photos from several cameras or zoom settings); default: one "
                "camera shared by all");
  cmd->add_option("--matcher", request->matcher,
                  "exhaustive: every pair (best up to a few hundred photos); sequential: each photo with its "
                  "neighbours in name order (video frames)")
      ->check(CLI::IsMember({"exhaustive", "sequential"}))
      ->default_val("exhaustive");
  cmd->add_flag("--no-intrinsics", *noIntrinsics,
                "Ignore PHOTOS/sparse/0's pinhole camera, which otherwise starts COLMAP's estimate (as EXIF focal "
                "lengths do for photographs)");
  cmd->add_flag("--force", request->force, "Replace OUTPUT when an earlier glint capture wrote it");
  cmd->add_option("--colmap", request->colmap, "The COLMAP program to run")->default_val("colmap");
  addThreadsFlag(cmd, &request->threads, "COLMAP's feature extraction, matching and mapping threads");
  cmd->callback([request, noIntrinsics]() {
    request->useKnownIntrinsics = !*noIntrinsics;
    CaptureResult result = reconstructCapture(*request);
    printSummary(*request, result);
  });
}

}  // namespace glint
