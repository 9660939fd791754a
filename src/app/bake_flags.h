// The --bake-reflections flags of `glint export`: bakes the scene's path-traced reflections
// into SH colours (render/sh_bake.h) with the settings the scene renders with.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "scene/gaussians.h"
#include "scene/splat_colour.h"
#include "train/train_config.h"

namespace glint {

class BakeFlags {
 public:
  // Declares --bake-reflections, --bake-directions, --bake-ridge, --seed and --device on cmd (the
  // degree is the export's --sh-degree, the cameras those of its --dataset).
  void add(CLI::App* cmd);
  bool given() const { return bake_; }
  // Throws Error when a baking flag is given without --bake-reflections.
  void check() const;

  // The baked colours (SH degree `degree`, radiance scaled by `exposure` before the
  // tonemap) of `scene`, loaded with `settings` (a run's, or a new run's defaults for a
  // bare .ply): its trace and render path settings, and the training cameras of `dataset`
  // (empty: the run's), which set the sampled directions.
  SplatColour bake(const GaussianScene& scene, const TrainConfig& settings, int degree, const std::string& dataset,
                   float exposure) const;

 private:
  CLI::App* cmd_ = nullptr;
  bool bake_ = false;
  int directions_ = 64;
  double ridge_ = 0.005;
  uint64_t seed_ = 0;
  std::string device_ = "auto";
};

}  // namespace glint
