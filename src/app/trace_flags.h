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
  // --backface-skip, --tracer and --device on cmd.
  void add(CLI::App* cmd);
  // `run` (a run's settings, or a new run's defaults for a bare .ply) with every flag the
  // user gave applied over it. The values are checked by TrainConfig::validate, so a flag
  // accepts what config.json accepts; only --bounces has its own range, as rendering may
  // follow longer paths than training. Call from the command's callback, once parsing is done.
  // --device picks the tracer unless --tracer names one: auto takes the GPU when there is
  // one. Prints the device chosen.
  SceneRendering resolve(TrainConfig run) const;

 private:
  bool given(const char* flag) const { return cmd_->get_option(flag)->count() > 0; }

  CLI::App* cmd_ = nullptr;
  TraceSettings trace_;
  int bounces_ = 0;
  float invalidNormalLength_ = 0;
  float backfaceSkip_ = 0;
  std::string tracer_ = "fast";
  std::string device_ = "auto";
};

// Declares --device (auto, cpu, cuda) on cmd, stored in *device.
void addDeviceFlag(CLI::App* cmd, std::string* device);

// The tracer kind for a --device value: `tracer` itself when the user gave --tracer (an
// error when it contradicts --device), else cuda for the GPU or `tracer` for the CPU.
// Prints "COMMAND: device: ..." (which GPU, or why the CPU).
std::string resolveTracerForDevice(const std::string& device, const std::string& tracer, bool tracerGiven,
                                   const std::string& command);

}  // namespace glint
