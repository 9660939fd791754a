// A tiny training run for the tests of the training loop and of the commands that read a
// run: a dataset of builtin:spheres small enough to train a few steps in well under a
// second, and a config that reaches reflections (and the far field) within those steps.
#pragma once

#include <filesystem>

#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"
#include "train/train_config.h"

namespace glint::test {

// 4 training and 2 test views of builtin:spheres at 24x18, 2 spp.
inline void makeTinyDataset(const std::filesystem::path& folder) {
  const SynthSettings tiny{.trainViews = 4, .testViews = 2, .width = 24, .height = 18, .spp = 2};
  generateDataset(makeBuiltinScene("spheres"), tiny, folder);
}

// `iters` steps of 256 rays on 2 threads, one reflected segment from step 3, scored every
// 4 steps and saved every 2.
inline TrainConfig tinyTrainConfig(const std::filesystem::path& dataset, int iters) {
  TrainConfig c;
  c.dataset = dataset.string();
  c.iters = iters;
  c.threads = 2;
  c.bounces = 1;
  c.reflectionWarmup = 2;
  c.batchRays = 256;
  c.evalEvery = 4;
  c.saveEvery = 2;
  c.farField.count = 300;  // the paper's 75,000 is for scenes of millions of pixels
  return c;
}

}  // namespace glint::test
