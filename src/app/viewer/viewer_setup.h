// Setting up a viewer the same way for `glint view` and `glint train --view`: the
// training cameras of a dataset, the default resolution and first camera, the host warning.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "app/viewer/viewer_server.h"
#include "scene/dataset.h"

namespace glint {

// The viewer's own flags, shared by both commands.
struct ViewerFlags {
  std::string host = "127.0.0.1";
  int port = 0;
  std::string resolution;  // "WxH"; empty: the dataset's, at most kDefaultMaxWidth wide
  int maxSamples = 1024;
};

// Wider datasets are shown at a reduced size by default: CPU rendering on a couple of cores.
constexpr int kDefaultMaxWidth = 640;

// Options for a viewer of a scene: cameras from the dataset (when given), the first
// training camera as the start (else one looking at the scene's centre from outside its
// bounds), the web folder beside the executable. Prints a warning for a non-loopback host.
ViewerOptions makeViewerOptions(const ViewerFlags& flags, const std::optional<Dataset>& dataset,
                                 const GaussianScene& scene, const std::filesystem::path& outputFolder);

// Blocks until SIGINT or SIGTERM (then restores the previous handlers).
void waitForInterrupt();

}  // namespace glint
