// The dataset the training benchmarks use when given none: builtin:spheres, 40 training
// views of 160x120 at 8 samples per pixel, rendered into a folder of their choosing.
#pragma once

#include <cstdio>
#include <filesystem>

#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"

namespace glint {

inline void renderTrainingBenchDataset(const std::filesystem::path& folder) {
  SynthSettings s;
  s.trainViews = 40;
  s.testViews = 2;
  s.width = 160;
  s.height = 120;
  s.spp = 8;
  std::fprintf(stderr, "rendering builtin:spheres (40 views, 160x120, 8 spp) into %s\n", folder.c_str());
  generateDataset(makeBuiltinScene("spheres"), s, folder);
}

}  // namespace glint
