// The trace-setting flags shared by `glint render` and `glint eval`: given flags override
// the settings a training run was made with, and the run's override the defaults.
#pragma once

#include <CLI/CLI.hpp>

#include "raytrace/trace_settings.h"

namespace glint {

class TraceFlags {
 public:
  // Declares --kernel-power, --alpha-min and --min-transmittance (and --tracer) on cmd.
  void add(CLI::App* cmd);
  // base with every flag the user gave on the command line applied over it. Call from the
  // command's callback, once parsing is done.
  TraceSettings apply(TraceSettings base) const;
  const std::string& tracer() const { return tracer_; }

 private:
  CLI::App* cmd_ = nullptr;
  TraceSettings flags_;
  std::string tracer_ = "fast";
};

}  // namespace glint
