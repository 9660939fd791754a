// How far a capture's training cameras (COLMAP's, or those a training run refined) are from the
// true cameras of the same photographs, up to the similarity that structure from motion cannot
// know (origin, orientation, scale): per view the angle between the rotations and the distance
// between the centres after the similarity, in the truth's units. Issue 44: whether camera
// refinement brings COLMAP's cameras nearer the truth. Prints a table and writes JSON (--json).
//
//   camera_error TRUTH ESTIMATE [--run RUN]... [--holdout N] [--json FILE]
//
// TRUTH and ESTIMATE are captures of the same photographs (e.g. `glint synth --layout capture`
// and `glint capture` of it); each --run is a training run of ESTIMATE whose checkpoint holds
// the refined poses (train/camera_refinement.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <tuple>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "math/nearest_rotation.h"
#include "math/percentile.h"
#include "scene/dataset.h"
#include "train/camera_refinement.h"
#include "train/checkpoint.h"

using namespace glint;

namespace {

struct CameraErrors {
  std::vector<float> degrees, distances;  // per view, the distance in the truth's units
  double ringSize = 0;                    // RMS distance of the true centres from their mean
  double frameDegrees = 0, frameScale = 1;  // the similarity's rotation angle and scale
};

// Errors of `estimate` against `truth` (the same views, in order) after the similarity
// between them, taken out as camera refinement takes a round's common motion out
// (removeCommonMotion): the estimate brought into the truth's frame.
CameraErrors compare(const std::vector<Camera>& truth, std::vector<Camera> estimate) {
  CameraErrors errors;
  std::tie(errors.frameDegrees, errors.frameScale) = removeCommonMotion(truth, &estimate);
  Vec3d meanTrue(0.0);
  for (const Camera& c : truth) meanTrue += c.position() / double(truth.size());
  double spread = 0;
  for (size_t v = 0; v < truth.size(); ++v) {
    spread += dot(truth[v].position() - meanTrue, truth[v].position() - meanTrue);
    errors.distances.push_back(float(length(estimate[v].position() - truth[v].position())));
    errors.degrees.push_back(float(rotationAngleDegrees(estimate[v].rotation() * truth[v].rotation().transposed())));
  }
  errors.ringSize = std::sqrt(spread / double(truth.size()));
  return errors;
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

std::vector<Camera> camerasOf(const DatasetSplit& split) {
  std::vector<Camera> cameras;
  for (size_t v = 0; v < split.views.size(); ++v) cameras.push_back(split.camera(v));
  return cameras;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scores a capture's training cameras, or a run's refined ones, against the true cameras"};
  std::string truthPath, estimatePath, jsonPath;
  std::vector<std::string> runs;
  int holdout = Dataset::kDefaultHoldout;
  app.add_option("truth", truthPath, "Capture with the true cameras")->required();
  app.add_option("estimate", estimatePath, "Capture of the same photographs with estimated cameras")->required();
  app.add_option("--run", runs, "Training run of ESTIMATE whose checkpoint holds refined poses (repeatable)");
  app.add_option("--holdout", holdout, "Every N-th view is a test view (as glint train --holdout)")
      ->check(CLI::Range(2, 1000));
  app.add_option("--json", jsonPath, "Write the errors here");
  CLI11_PARSE(app, argc, argv);
  try {
    const Dataset truth = Dataset::open(truthPath, false, holdout), estimate = Dataset::open(estimatePath, false, holdout);
    const DatasetSplit& trueSplit = truth.train();
    const DatasetSplit& estimateSplit = estimate.train();
    if (trueSplit.views.size() != estimateSplit.views.size())
      throw Error(estimatePath, "has " + std::to_string(estimateSplit.views.size()) + " training views, " + truthPath +
                                    " " + std::to_string(trueSplit.views.size()) + " (the same photographs are needed)");
    for (size_t v = 0; v < trueSplit.views.size(); ++v)
      if (std::filesystem::path(trueSplit.views[v].filePath).filename() !=
          std::filesystem::path(estimateSplit.views[v].filePath).filename())
        throw Error(estimatePath, "training view " + std::to_string(v) + " is " + estimateSplit.views[v].filePath +
                                      ", the truth's " + trueSplit.views[v].filePath);
    const std::vector<Camera> trueCameras = camerasOf(trueSplit);

    std::vector<std::pair<std::string, std::vector<Camera>>> rows{{"estimate", camerasOf(estimateSplit)}};
    for (const std::string& run : runs) {
      const std::filesystem::path file = std::filesystem::path(run) / "checkpoint" / "state.bin";
      TrainingState state = readCheckpoint(file);
      std::vector<Camera> refined = rows.front().second;  // as COLMAP left them when never refined
      if (!state.cameraPoses.empty() && state.cameraPoses.size() != refined.size())
        throw Error(file.string(), "holds " + std::to_string(state.cameraPoses.size()) + " poses for " +
                                       std::to_string(refined.size()) + " training views");
      for (size_t v = 0; v < state.cameraPoses.size(); ++v) refined[v].cameraToWorld = state.cameraPoses[v];
      rows.emplace_back(run, refined);
    }
    nlohmann::json out = nlohmann::json::array();
    std::printf("%d training views; position errors in the truth's units\n", int(trueCameras.size()));
    // "frame": the similarity's rotation and scale; between two runs of one capture they say
    // how far the cameras moved together (a drift of the whole frame) rather than apart.
    std::printf("%-40s %9s %9s %9s %10s %10s %10s %8s %10s %10s\n", "cameras", "deg mean", "deg med", "deg max",
                "pos mean", "pos med", "pos max", "% ring", "frame deg", "frame scl");
    for (const auto& [name, cameras] : rows) {
      const CameraErrors e = compare(trueCameras, cameras);
      const double positionMean = mean(e.distances);
      std::printf("%-40s %9.3f %9.3f %9.3f %10.4f %10.4f %10.4f %8.2f %10.4f %10.5f\n", name.c_str(),
                  mean(e.degrees), percentileOf(e.degrees, 0.5), percentileOf(e.degrees, 1.0), positionMean,
                  percentileOf(e.distances, 0.5), percentileOf(e.distances, 1.0), 100.0 * positionMean / e.ringSize,
                  e.frameDegrees, e.frameScale);
      out.push_back({{"cameras", name},
                     {"degrees_mean", mean(e.degrees)},
                     {"degrees_median", percentileOf(e.degrees, 0.5)},
                     {"degrees_max", percentileOf(e.degrees, 1.0)},
                     {"position_mean", positionMean},
                     {"position_median", percentileOf(e.distances, 0.5)},
                     {"position_max", percentileOf(e.distances, 1.0)},
                     {"ring_size", e.ringSize},
                     {"frame_degrees", e.frameDegrees},
                     {"frame_scale", e.frameScale}});
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(2) << "\n";
  } catch (const Error& e) {
    std::fprintf(stderr, "camera_error: %s\n", e.what());
    return 1;
  }
  return 0;
}
