// The small training set of the trainer's tests (tests/train, and tests/cuda on a GPU):
// builtin:spheres path-traced into 24 training and 4 test views at 64x48 (8 spp, 3 bounces),
// its training views loaded, and trainers started from its dense initialisation.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "io/temp_folder.h"
#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"
#include "train/camera_culling.h"
#include "train/dense_init.h"
#include "train/scene_extent.h"
#include "train/trainer.h"

namespace glint::test {

struct SmallTrainingSet {
  TempFolder folder;
  std::unique_ptr<Dataset> dataset;
  std::unique_ptr<TrainingViews> views;

  static std::unique_ptr<SmallTrainingSet> make() {
    auto set = std::make_unique<SmallTrainingSet>();
    SynthSettings s;
    s.trainViews = 24;
    s.testViews = 4;
    s.width = 64;
    s.height = 48;
    s.spp = 8;
    s.bounces = 3;
    generateDataset(makeBuiltinScene("spheres"), s, set->folder.path());
    set->dataset = std::make_unique<Dataset>(Dataset::open(set->folder.path()));
    set->views = std::make_unique<TrainingViews>(TrainingViews::load(*set->dataset, set->dataset->train()));
    return set;
  }

  // A trainer from the dense initialisation of the depth buffers (black colours if asked).
  std::unique_ptr<Trainer> trainer(const TrainConfig& c, const std::string& tracer = "fast", bool black = false) const {
    DenseInitSettings init;
    init.forceDepthBuffers = true;
    GaussianScene scene = denseInitialisation(*dataset, init).scene;
    if (black) std::fill(scene.diffuse.begin(), scene.diffuse.end(), Rgb(0.0f));
    return std::make_unique<Trainer>(c, *views, cameraSpheres(*dataset, dataset->train()), std::move(scene),
                                     sceneExtent(dataset->train()), tracer);
  }
  // A trainer that goes on from `state`.
  std::unique_ptr<Trainer> resumed(const TrainConfig& c, TrainingState state, const std::string& tracer = "fast") const {
    return std::make_unique<Trainer>(c, *views, cameraSpheres(*dataset, dataset->train()), std::move(state), tracer);
  }
};

}  // namespace glint::test
