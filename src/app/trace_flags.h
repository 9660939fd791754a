// The trace- and path-setting flags shared by `glint render` and `glint eval`: given flags
// override the settings a training run was made with (its config.json), and the run's
// override the defaults.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "raytrace/trace_settings.h"
#include "render/gaussian_path.h"
#include "train/train_config.h"

namespace glint {

// How a scene is rendered: what the run trained with, and the flags over it.
struct SceneRendering {
  TraceSettings trace;
  PathSettings path;
  std::string tracer;  // Gaussian tracer kind
};

class TraceFlags {
 public:
  // Declares --kernel-power, --alpha-min, --min-transmittance, --bounces, --invalid-normal,
  // --backface-skip and --tracer on cmd.
  void add(CLI::App* cmd);
  // `run` (a run's settings, or a new run's defaults for a bare .ply) with every flag the
  // user gave applied over it. The values are checked by TrainConfig::validate, so a flag
  // accepts what config.json accepts; only --bounces has its own range, as rendering may
  // follow longer paths than training. Call from the command's callback, once parsing is done.
  SceneRendering resolve(TrainConfig run) const;

 private:
  bool given(const char* flag) const { return cmd_->get_option(flag)->count() > 0; }

  CLI::App* cmd_ = nullptr;
  TraceSettings trace_;
  int bounces_ = 0;
  float invalidNormalLength_ = 0;
  float backfaceSkip_ = 0;
  std::string tracer_ = "fast";
};

}  // namespace glint
