// The --bake-reflections flags of `glint export`: bakes the scene's path-traced reflections
// into SH colours (render/sh_bake.h) with the settings the scene renders with.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "scene/gaussians.h"
#include "scene/splat_colour.h"

namespace glint {

class BakeFlags {
 public:
  // Declares --bake-reflections, --sh-degree, --bake-directions, --bake-ridge, --dataset
  // and --seed on cmd.
  void add(CLI::App* cmd);
  bool given() const { return bake_; }
  // Throws Error when a baking flag is given without --bake-reflections.
  void check() const;

  // The baked colours of `scene`, read from `input` (a run folder, whose config.json gives
  // the trace and path settings and the dataset whose training cameras set the sampled
  // directions; or a .ply, rendered with a new run's defaults).
  SplatColour bake(const std::filesystem::path& input, const GaussianScene& scene) const;

 private:
  CLI::App* cmd_ = nullptr;
  bool bake_ = false;
  int shDegree_ = 3;
  int directions_ = 64;
  double ridge_ = 0.005;
  std::string dataset_;
  uint64_t seed_ = 0;
};

}  // namespace glint
