// Where a command's Gaussian scene comes from: a .ply file, or a training run folder whose
// config.json also names the dataset and the settings the scene was trained with.
#pragma once

#include <filesystem>

#include "scene/gaussians.h"
#include "train/train_config.h"

namespace glint {

struct SceneSource {
  GaussianScene scene;
  // The run's settings (RunFolder::readConfig), or a new run's defaults for a bare .ply or
  // a run folder without config.json: settings.trace and settings.path() say how the
  // scene renders, settings.dataset (empty if unknown) what it was trained on.
  TrainConfig settings;
};

// p is either a Gaussian scene .ply, or a training run folder: RUN/scene.ply is required,
// and RUN/config.json is read if present. Throws Error naming the folder or the file that
// is missing, corrupt or out of range (the same message as every command reading a run).
SceneSource loadSceneSource(const std::filesystem::path& p);

}  // namespace glint
