// The trace-setting flags shared by `glint render` and `glint eval`: given flags override
// the settings a training run was made with, and the run's override the defaults.
#pragma once

#include <CLI/CLI.hpp>

#include "raytrace/trace_settings.h"
#include "render/gaussian_path.h"

namespace glint {

class TraceFlags {
 public:
  // Declares --kernel-power, --alpha-min, --min-transmittance, --tracer, --bounces and
  // --invalid-normal on cmd.
  void add(CLI::App* cmd);
  // base with every flag the user gave on the command line applied over it. Call from the
  // command's callback, once parsing is done.
  TraceSettings apply(TraceSettings base) const;
  const std::string& tracer() const { return tracer_; }
  // The path settings: --bounces and --invalid-normal.
  const PathSettings& path() const { return path_; }

 private:
  CLI::App* cmd_ = nullptr;
  TraceSettings flags_;
  std::string tracer_ = "fast";
  PathSettings path_ = [] {
    PathSettings p;
    p.bounces = 2;  // the paper's path length 3
    return p;
  }();
};

}  // namespace glint
