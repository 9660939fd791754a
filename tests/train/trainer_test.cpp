// The training loop end to end on a tiny dataset made by the ground-truth generator: the
// loss falls and the test views improve on the initialisation; a resumed run is bit-exact.
#include "train/trainer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/parallel.h"
#include "io/temp_folder.h"
#include "synth/builtin_scenes.h"
#include "synth/dataset_generator.h"
#include "train/camera_culling.h"
#include "train/dense_init.h"
#include "train/far_field.h"
#include "raytrace/gaussian_kernel.h"
#include "train/scene_extent.h"
#include "train/training_eval.h"

namespace glint {
namespace {

class TrainerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new test::TempFolder();
    SynthSettings s;
    s.trainViews = 24;
    s.testViews = 4;
    s.width = 64;
    s.height = 48;
    s.spp = 8;
    s.bounces = 3;
    generateDataset(makeBuiltinScene("spheres"), s, folder_->path());
    dataset_ = new Dataset(Dataset::open(folder_->path()));
    views_ = new TrainingViews(TrainingViews::load(*dataset_, dataset_->train()));
  }
  static void TearDownTestSuite() {
    delete views_;
    delete dataset_;
    delete folder_;
  }

  static TrainConfig smallConfig() {
    TrainConfig c;
    c.dataset = folder_->path().string();
    c.batchRays = 2048;
    c.batchViews = 2;
    c.prune.start = 100;
    c.prune.every = 50;
    c.bounces = 0;
    c.farField.count = 2000;  // the paper's 75,000 is for scenes of millions of pixels
    return c;
  }
  static std::unique_ptr<Trainer> makeTrainer(const TrainConfig& c, bool black = false) {
    DenseInitSettings init;
    init.forceDepthBuffers = true;
    GaussianScene scene = denseInitialisation(*dataset_, init).scene;
    if (black) std::fill(scene.diffuse.begin(), scene.diffuse.end(), Rgb(0.0f));
    return std::make_unique<Trainer>(c, *views_, cameraSpheres(*dataset_, dataset_->train()), std::move(scene),
                                     sceneExtent(dataset_->train()));
  }

  static test::TempFolder* folder_;
  static Dataset* dataset_;
  static TrainingViews* views_;
};

test::TempFolder* TrainerTest::folder_ = nullptr;
Dataset* TrainerTest::dataset_ = nullptr;
TrainingViews* TrainerTest::views_ = nullptr;

TEST_F(TrainerTest, LossFallsAndTestViewsImprove) {
  TrainConfig c = smallConfig();
  std::unique_ptr<Trainer> trainer = makeTrainer(c);
  TestViews test = TestViews::load(*dataset_, dataset_->test(), 4);
  TestScore before = test.score(trainer->tracer(), 4);
  // Mean loss over windows of 50 steps: each window below the one before.
  std::vector<double> windows;
  double sum = 0;
  for (int step = 1; step <= 300; ++step) {
    StepReport r = trainer->step();
    EXPECT_EQ(r.overflowedRays, 0);
    sum += r.loss;
    if (step % 50 == 0) {
      windows.push_back(sum / 50);
      sum = 0;
    }
  }
  for (size_t k = 1; k < windows.size(); ++k) EXPECT_LT(windows[k], windows[k - 1]) << "window " << k;
  EXPECT_LT(windows.back(), 0.5 * windows.front());
  TestScore after = test.score(trainer->tracer(), 4);
  EXPECT_GT(after.diffusePsnr, before.diffusePsnr + 5.0) << "before " << before.diffusePsnr;
  EXPECT_LT(after.normalDegrees, before.normalDegrees - 10.0) << "before " << before.normalDegrees;
}

// From black initial colours, L_r as the only colour loss (no L_d; the G-buffer terms shape
// the paths) lowers the specular error: its gradient reaches the
// Gaussians the reflected segments hit. The same run with L_r's weight 0 is the baseline.
TEST_F(TrainerTest, ReflectionLossLowersTheSpecularError) {
  auto specularErrorAfterTraining = [&](float weight) {
    TrainConfig c = smallConfig();
    c.bounces = 1;
    c.reflectionWarmup = 50;
    c.loss = LossWeights{0, 2.5f, 2.5f, 1, 1, weight};  // no L_d: diffuse colours learn only from L_r
    c.lr.normal = c.lr.f0 = 0.02f;  // valid normals and F0 within the short warm-up
    std::unique_ptr<Trainer> trainer = makeTrainer(c, /*black=*/true);
    double late = 0;
    for (int step = 1; step <= 300; ++step) {
      StepReport r = trainer->step();
      EXPECT_EQ(r.overflowedRays, 0);
      if (step <= 50) {
        EXPECT_EQ(r.terms.specular, 0.0) << "reflections start after the warm-up";
      }
      if (step > 250) late += r.terms.specular / 50;
      if (step == 300) {
        EXPECT_GT(r.reflectedSegments, r.rays / 2) << "most paths should reflect by now";
      }
    }
    return late;
  };
  double without = specularErrorAfterTraining(0.0f);
  double with = specularErrorAfterTraining(3.0f);
  EXPECT_LT(with, 0.9 * without) << "with L_r " << with << ", without " << without;
  std::printf("specular L1 with L_r %.4f, without %.4f\n", with, without);
}

template <typename V>
bool sameTrainerBytes(const std::vector<V>& a, const std::vector<V>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(V)) == 0;
}

// The RGB-only baseline's colour target is the render buffer. Targets are stored with a
// shared exponent: each channel to 9 bits of the pixel's largest one (absolutely to 2^-25
// below 2^-16, the format's smallest exponent).
TEST_F(TrainerTest, RenderColourTargetHoldsTheRenderBuffer) {
  TrainingViews rgb = TrainingViews::load(*dataset_, dataset_->train(), ColourTarget::Render);
  EXPECT_TRUE(rgb.supervised().finalColour);
  EXPECT_FALSE(views_->supervised().finalColour);
  Image render = dataset_->loadBuffer(dataset_->train(), 3, Buffer::Render);
  Image diffuse = dataset_->loadBuffer(dataset_->train(), 3, Buffer::Diffuse);
  auto packingError = [](const Rgb& stored, const Rgb& truth) {
    float largest = std::max({truth.x, truth.y, truth.z});
    return std::max({std::abs(stored.x - truth.x), std::abs(stored.y - truth.y), std::abs(stored.z - truth.z)}) /
           std::max(largest, 512.0f * kSmallestSharedExponentError);
  };
  float renderError = 0, diffuseError = 0;
  for (int y = 0; y < render.height; ++y)
    for (int x = 0; x < render.width; ++x) {
      size_t pixel = size_t(y) * size_t(render.width) + size_t(x);
      renderError = std::max(renderError, packingError(rgb.target(3, pixel).diffuse, render.rgb(x, y)));
      diffuseError = std::max(diffuseError, packingError(views_->target(3, pixel).diffuse, diffuse.rgb(x, y)));
    }
  EXPECT_LE(renderError, 1.0f / 512.0f);
  EXPECT_LE(diffuseError, 1.0f / 512.0f);
}

// A predictor may give only some buffers: a dataset without diffuse, specular, roughness
// and F0 trains on its render images as final colours, with the depth and normal losses.
TEST_F(TrainerTest, MissingBufferKindsTrainWithoutTheirLosses) {
  test::TempFolder copy;
  std::filesystem::copy(folder_->path(), copy.path(), std::filesystem::copy_options::recursive);
  for (const char* kind : {"diffuse", "specular", "roughness", "f0"})
    std::filesystem::remove_all(copy.path() / "train" / kind);
  Dataset partial = Dataset::open(copy.path());
  TrainingViews views = TrainingViews::load(partial, partial.train());
  const SupervisedBuffers& s = views.supervised();
  EXPECT_TRUE(s.finalColour);
  EXPECT_TRUE(s.depth && s.normal);
  EXPECT_FALSE(s.specular || s.roughness || s.f0);
  EXPECT_EQ(s.list(false), "specular, roughness, f0");

  TrainConfig c = smallConfig();
  c.bounces = 1;
  c.reflectionWarmup = 0;
  DenseInitSettings init;
  init.forceDepthBuffers = true;
  Trainer trainer(c, views, cameraSpheres(partial, partial.train()), denseInitialisation(*dataset_, init).scene,
                  sceneExtent(partial.train()));
  StepReport first = trainer.step();
  EXPECT_EQ(first.terms.roughness, 0.0);
  EXPECT_EQ(first.terms.f0, 0.0);
  EXPECT_EQ(first.terms.specular, 0.0);
  EXPECT_GT(first.terms.diffuse, 0.0);
  EXPECT_GT(first.terms.normal, 0.0);
  double lastLoss = 0;
  for (int i = 0; i < 30; ++i) lastLoss = trainer.step().loss;
  EXPECT_LT(lastLoss, first.loss);
}

// The shift-invariant roughness term: the initialisation's roughness is far under the
// priors (the reported offset, the median of prior - model, is large). The absolute term
// closes that offset; the shift-invariant one takes it out of the priors, and no other term
// reaches roughness, so it stays, or nearly.
TEST_F(TrainerTest, ShiftInvariantRoughnessTermLeavesAConstantOffsetAlone) {
  TrainConfig c = smallConfig();
  std::unique_ptr<Trainer> absolute = makeTrainer(c);
  c.roughnessShiftInvariant = true;
  std::unique_ptr<Trainer> invariant = makeTrainer(c);
  const float start = absolute->step().roughnessOffset;
  EXPECT_EQ(invariant->step().roughnessOffset, start);  // the first step has no shift yet
  EXPECT_GT(start, 0.2f);
  StepReport a, b;
  for (int i = 0; i < 60; ++i) a = absolute->step(), b = invariant->step();
  // Measured: 0.42 to 0.29 and to 0.38 (the rendered roughness also follows the opacities
  // the other terms train).
  const float closedAbsolute = start - a.roughnessOffset, closedInvariant = start - b.roughnessOffset;
  EXPECT_GT(closedAbsolute, 0.08f);
  EXPECT_LT(closedInvariant, 0.4f * closedAbsolute);
}

// Carving keeps far-field Gaussians only where no training view records free space, with
// their support behind every recorded surface.
TEST_F(TrainerTest, FarFieldIsCarvedOutOfObservedFreeSpace) {
  TrainConfig c = smallConfig();
  SceneSphere sphere = sceneSphere(dataset_->train());
  GaussianScene far = farFieldGaussians(c.farField, Vec3f(sphere.centre), sphere.radius, 5);
  const size_t before = far.size();
  size_t removed = carveObservedFreeSpace(&far, *views_, c.trace);
  EXPECT_EQ(far.size(), before - removed);
  EXPECT_GT(removed, 0u);
  EXPECT_GT(far.size(), 0u);
  size_t checked = 0;
  for (size_t i = 0; i < far.size(); ++i) {
    const double support = proxyRadius(double(far.opacity(i)), c.trace) * double(far.scale(i).x);
    for (size_t v = 0; v < views_->viewCount(); ++v) {
      const Camera& camera = views_->camera(v);
      Vec2d pixel;
      if (!camera.project(camera.cameraToWorld.inverse(), Vec3d(far.position[i]), &pixel)) continue;
      const PixelTarget& t = views_->target(v, size_t(pixel.y) * size_t(camera.width) + size_t(pixel.x));
      if (!t.surface) continue;
      double distance = length(Vec3d(far.position[i]) - camera.position());
      EXPECT_GE(distance - support, double(t.depth) * (1 - 1e-5)) << "Gaussian " << i << " view " << v;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
}

// When reflections start, the far-field Gaussians join the scene (outside every camera
// sphere) and the optimiser's state grows with them; training continues over them.
TEST_F(TrainerTest, FarFieldGaussiansJoinWhenReflectionsStart) {
  TrainConfig c = smallConfig();
  c.bounces = 1;
  c.reflectionWarmup = 5;
  std::unique_ptr<Trainer> trainer = makeTrainer(c);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(trainer->step().farFieldAdded, 0u);
  const size_t before = trainer->scene().size();
  StepReport r = trainer->step();
  EXPECT_GT(r.farFieldAdded, size_t(c.farField.count) / 2);
  EXPECT_LE(r.farFieldAdded, size_t(c.farField.count));
  ASSERT_EQ(trainer->scene().size(), before + r.farFieldAdded);
  GaussianScene added;
  for (size_t i = before; i < trainer->scene().size(); ++i) added.append(trainer->scene(), i);
  std::vector<bool> outside = outsideCameraSpheres(added, cameraSpheres(*dataset_, dataset_->train()),
                                                   CullRegion::WholeSphere);
  EXPECT_EQ(size_t(std::count(outside.begin(), outside.end(), true)), added.size())
      << "far-field Gaussians near a camera must be culled";
  for (int i = 0; i < 3; ++i) {
    StepReport later = trainer->step();
    EXPECT_EQ(later.farFieldAdded, 0u);
    EXPECT_TRUE(std::isfinite(later.loss));
    EXPECT_EQ(later.overflowedRays, 0);
  }
}

// With threshold_pixels the pruning threshold scales with the views' pixel count: set to
// the views' own size it prunes exactly as the unscaled threshold; set to 46 times it (the
// paper's 1152x768 against 160x120) the threshold is 46 times lower and fewer go.
TEST_F(TrainerTest, PruningThresholdScalesWithThePixelCount) {
  TrainConfig c = smallConfig();
  c.prune.start = 20;
  c.prune.every = 10;
  c.prune.weightThreshold = 0.5f;
  auto sizeAfter = [&](double thresholdPixels) {
    TrainConfig scaled = c;
    scaled.prune.thresholdPixels = thresholdPixels;
    std::unique_ptr<Trainer> t = makeTrainer(scaled);
    for (int i = 0; i < 30; ++i) t->step();
    return t->scene().size();
  };
  const size_t unscaled = sizeAfter(0.0);
  EXPECT_LT(unscaled, makeTrainer(c)->scene().size()) << "pruning should have removed Gaussians";
  EXPECT_EQ(sizeAfter(views_->meanPixelsPerView()), unscaled);
  EXPECT_GT(sizeAfter(46.0 * views_->meanPixelsPerView()), unscaled);
}

// Densification splits the chosen share of the Gaussians at its steps only, and the run
// goes on with the children (their Adam moments copied from the parents).
TEST_F(TrainerTest, DensificationSplitsTheChosenShareOnSchedule) {
  TrainConfig c = smallConfig();
  c.prune.start = 1000;  // no pruning: the count changes by the splits alone
  c.densify.fraction = 0.1f;
  c.densify.every = 5;
  c.densify.start = 10;
  c.densify.stop = 15;
  std::unique_ptr<Trainer> t = makeTrainer(c);
  std::vector<size_t> splits;
  for (int i = 0; i < 20; ++i) {
    const size_t before = t->scene().size();
    const StepReport r = t->step();
    EXPECT_EQ(r.gaussians, before + r.split);
    splits.push_back(r.split);
  }
  for (int i = 0; i < 20; ++i) {
    const int stepAfter = i + 1;
    if (stepAfter == 10 || stepAfter == 15)
      EXPECT_GT(splits[size_t(i)], 0u) << stepAfter;
    else
      EXPECT_EQ(splits[size_t(i)], 0u) << stepAfter;
  }
  const size_t initial = makeTrainer(c)->scene().size();
  EXPECT_EQ(splits[9], size_t(std::ceil(0.1 * double(initial))));
  const GaussianScene& scene = t->scene();
  for (size_t i = 0; i < scene.size(); ++i) ASSERT_TRUE(std::isfinite(scene.position[i].x)) << i;
}

TEST_F(TrainerTest, ResumedRunIsBitExact) {
  TrainConfig c = smallConfig();
  c.bounces = 1;  // reflections and the far-field Gaussians start after the resume
  c.reflectionWarmup = 30;
  c.farField.count = 500;
  c.prune.start = 20;  // prunes (and rebuilds the tracer) on both sides of the resume
  c.prune.every = 10;
  c.prune.weightThreshold = 0.5f;
  c.densify.fraction = 0.05f;  // splits (and their accumulated scores) on both sides too
  c.densify.every = 10;
  c.densify.start = 20;
  c.densify.stop = 40;
  c.roughnessShiftInvariant = true;  // its offset, carried by the checkpoint
  std::unique_ptr<Trainer> straight = makeTrainer(c);
  for (int i = 0; i < 50; ++i) straight->step();

  std::unique_ptr<Trainer> first = makeTrainer(c);
  for (int i = 0; i < 25; ++i) first->step();
  test::TempFolder temp;
  writeCheckpoint(temp.path() / "state.bin", first->state());
  first.reset();
  Trainer resumed(c, *views_, cameraSpheres(*dataset_, dataset_->train()), readCheckpoint(temp.path() / "state.bin"));
  for (int i = 0; i < 25; ++i) resumed.step();

  const GaussianScene& a = straight->scene();
  const GaussianScene& b = resumed.scene();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LT(a.size(), makeTrainer(c)->scene().size()) << "pruning should have removed Gaussians";
  EXPECT_TRUE(sameTrainerBytes(a.position, b.position));
  EXPECT_TRUE(sameTrainerBytes(a.rotation, b.rotation));
  EXPECT_TRUE(sameTrainerBytes(a.logScale, b.logScale));
  EXPECT_TRUE(sameTrainerBytes(a.opacityLogit, b.opacityLogit));
  EXPECT_TRUE(sameTrainerBytes(a.diffuse, b.diffuse));
  EXPECT_TRUE(sameTrainerBytes(a.normal, b.normal));
  EXPECT_TRUE(sameTrainerBytes(a.roughness, b.roughness));
  EXPECT_TRUE(sameTrainerBytes(a.f0, b.f0));
}

}  // namespace
}  // namespace glint
