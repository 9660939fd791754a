// Where a command's Gaussian scene comes from: a .ply file, or a training run folder whose
// config.json also names the dataset and the settings the scene was trained with.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "scene/gaussian_ply.h"
#include "scene/gaussians.h"
#include "train/train_config.h"

namespace glint {

struct SceneSource {
  GaussianScene scene;
  // The run's settings (RunFolder::readConfig), or a new run's defaults for a bare .ply or
  // a run folder without config.json: settings.trace and settings.path() say how the
  // scene renders, settings.dataset (empty if unknown) what it was trained on.
  TrainConfig settings;
  std::filesystem::path sceneFile;  // the .ply that was read
  GaussianPlyImport import;         // its layout, and what a 3DGS import did
};

// p is either a Gaussian scene .ply, or a training run folder: RUN/scene.ply is required,
// and RUN/config.json is read if present. `layout` is --input-layout (Auto: detected, see
// detectGaussianPlyLayout). A 3DGS import says on stderr how its colour and materials were
// set, and warns when view-dependent colour (f_rest) is dropped. Throws Error naming the
// folder or the file that is missing, corrupt, ambiguous or out of range (the same message
// as every command reading a run).
SceneSource loadSceneSource(const std::filesystem::path& p, PlyLayout layout = PlyLayout::Auto);

// Registers --input-layout auto|glint|3dgs on a command that loads a scene, into `layout`
// (default "auto"); parseInputLayout turns the checked value into a PlyLayout.
void addInputLayoutFlag(CLI::App& command, std::string& layout);
PlyLayout parseInputLayout(const std::string& name);

}  // namespace glint
