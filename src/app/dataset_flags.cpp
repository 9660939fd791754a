// --downscale and --background: their help, ranges, and how they override a run's settings.
#include "app/dataset_flags.h"

namespace glint {

void DatasetFlags::add(CLI::App* cmd, bool withBackground) {
  cmd_ = cmd;
  cmd->add_option("--downscale", downscale_,
                  "Use every view at 1/N resolution, N in [" + std::to_string(kDownscaleRange.min) + ", " +
                      std::to_string(kDownscaleRange.max) +
                      "]: images and buffers box-filtered over N x N pixels (normals averaged and renormalised, "
                      "depth over the surface pixels), focal lengths and principal point divided by N, and the "
                      "last width % N columns and height % N rows dropped (docs/data-format.md). Default 1; "
                      "eval and render default to the run's")
      ->check(CLI::Range(kDownscaleRange.min, kDownscaleRange.max));
  if (withBackground)
    cmd->add_option("--background", background_,
                    "white or black: the colour behind the transparent pixels of a NeRF-synthetic dataset's RGBA "
                    "images, composited in linear values (docs/data-format.md). Default white, as NeRF-synthetic "
                    "results are usually reported; eval defaults to the run's")
        ->check(CLI::IsMember(choiceNames<AlphaBackground>()));
}

void DatasetFlags::applyTo(TrainConfig* run) const {
  if (given("--downscale")) run->downscale = downscale_;
  if (given("--background")) run->background = *choiceFromName<AlphaBackground>(background_);  // IsMember checked it
}

DatasetReading DatasetFlags::resolve(TrainConfig run, bool requireBuffers) const {
  applyTo(&run);
  return run.datasetReading(requireBuffers);
}

}  // namespace glint
