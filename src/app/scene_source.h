// Where a command's Gaussian scene comes from: a .ply file, or a training run folder whose
// config.json also names the dataset and the trace settings the scene was trained with.
#pragma once

#include <filesystem>

#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

struct SceneSource {
  GaussianScene scene;
  TraceSettings trace;            // the run's settings, or the defaults for a bare .ply
  std::filesystem::path dataset;  // the run's dataset; empty if unknown
};

// p is either a Gaussian scene .ply (read with default TraceSettings), or a training run
// folder: RUN/scene.ply is required, and RUN/config.json is read if present, taking
// "dataset" (a path string, kept as written: the trainer writes it absolute) and
// "trace": {"kernel_power", "alpha_min", "min_transmittance"} (numbers, each optional,
// within the ranges the command-line flags accept) and "exact_tail" (a boolean). Throws Error naming the folder or the
// file that is missing, corrupt or out of range.
SceneSource loadSceneSource(const std::filesystem::path& p);

}  // namespace glint
