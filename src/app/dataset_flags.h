// The flags that say how a command reads its dataset, shared by `glint train`, `eval` and
// `render`: --downscale N and --background white|black. Flags given override the settings
// a training run was made with (its config.json), as the trace flags do.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "scene/dataset.h"
#include "train/train_config.h"

namespace glint {

class DatasetFlags {
 public:
  // Declares --downscale and, when withBackground, --background on cmd.
  void add(CLI::App* cmd, bool withBackground);
  // `run` (a run's settings, or the defaults for a bare .ply) with the flags given applied.
  void applyTo(TrainConfig* run) const;
  // How to open the dataset for `run`, with the flags given applied.
  DatasetReading resolve(TrainConfig run, bool requireBuffers) const;

 private:
  bool given(const char* flag) const {
    const CLI::Option* option = cmd_->get_option_no_throw(flag);
    return option && option->count() > 0;
  }

  CLI::App* cmd_ = nullptr;
  int downscale_ = 1;
  std::string background_;
};

}  // namespace glint
