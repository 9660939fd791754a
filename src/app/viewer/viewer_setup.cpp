// Shared setup of the viewer for the view and train commands.
#include "app/viewer/viewer_setup.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "app/cli_parsing.h"
#include "app/viewer/static_files.h"
#include "core/error.h"

namespace glint {

namespace {

std::atomic<bool> gStopViewer{false};
extern "C" void onViewerInterrupt(int) { gStopViewer = true; }

bool isLoopback(const std::string& host) {
  return host == "127.0.0.1" || host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

// Looks at the centre of the Gaussians' means from outside their bounds, along +z.
ViewerCamera overviewCamera(const GaussianScene& scene) {
  ViewerCamera camera;
  if (scene.empty()) return camera;
  Vec3f lo = scene.position[0], hi = scene.position[0];
  for (const Vec3f& p : scene.position) lo = min(lo, p), hi = max(hi, p);
  Vec3d center = Vec3d((lo + hi) * 0.5f);
  double radius = std::max(0.5 * double(length(hi - lo)), 1e-3);
  camera.eye = center + Vec3d(0, 0.3 * radius, 2.2 * radius);
  camera.forward = normalize(center - camera.eye);
  return camera;
}

}  // namespace

ViewerOptions makeViewerOptions(const ViewerFlags& flags, const std::optional<Dataset>& dataset,
                                const GaussianScene& scene, const std::filesystem::path& outputFolder) {
  ViewerOptions options;
  options.host = flags.host;
  options.port = flags.port;
  options.maxSamples = flags.maxSamples;
  options.outputFolder = outputFolder;
  options.webRoot = findWebFolder();
  if (options.webRoot.empty())
    std::fprintf(stderr, "glint view: warning: no web folder beside the executable; only the API is served\n");
  if (!isLoopback(flags.host))
    std::fprintf(stderr,
                 "glint view: warning: listening on %s, not loopback: anyone who can reach this machine can view "
                 "the scene, and anyone who sees the printed URL (its token travels unencrypted) can edit it and "
                 "write files into %s\n",
                 flags.host.c_str(), outputFolder.string().c_str());

  options.initialCamera = overviewCamera(scene);
  if (dataset) {
    for (const DatasetSplit* split : {&dataset->train(), &dataset->test()})
      for (size_t i = 0; i < split->views.size(); ++i)
        options.trainingCameras.push_back(
            {split->name + " " + std::to_string(i),
             ViewerCamera::fromCamera(split->views[i].camera)});
    if (!options.trainingCameras.empty()) options.initialCamera = options.trainingCameras[0].camera;
  }

  if (!flags.resolution.empty()) {
    Vec2i r = parseResolution(flags.resolution, "--res");
    options.width = r.x, options.height = r.y;
  } else if (dataset && !dataset->train().views.empty()) {
    // The size of the first training image, when the dataset has its images.
    std::optional<std::filesystem::path> first = dataset->findBufferFile(dataset->train().views[0], Buffer::Render);
    if (first) {
      Image image = readImage(*first);
      int divisor = (image.width + kDefaultMaxWidth - 1) / kDefaultMaxWidth;
      options.width = image.width / divisor, options.height = image.height / divisor;
    }
  }
  return options;
}

void waitForInterrupt() {
  gStopViewer = false;
  auto previousInt = std::signal(SIGINT, onViewerInterrupt);
  auto previousTerm = std::signal(SIGTERM, onViewerInterrupt);
  while (!gStopViewer) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::signal(SIGINT, previousInt);
  std::signal(SIGTERM, previousTerm);
}

}  // namespace glint
