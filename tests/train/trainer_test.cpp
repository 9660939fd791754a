// The training loop end to end on a tiny dataset made by the ground-truth generator: the
// loss falls and the test views improve on the initialisation; a resumed run is bit-exact.
#include "train/trainer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <span>

#include "common/relative_difference.h"
#include "common/small_training_set.h"
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
    set_ = test::SmallTrainingSet::make().release();
    dataset_ = set_->dataset.get();
    views_ = set_->views.get();
  }
  static void TearDownTestSuite() { delete set_; }

  static TrainConfig smallConfig() {
    TrainConfig c;
    c.dataset = set_->folder.path().string();
    c.batchRays = 2048;
    c.batchViews = 2;
    c.prune.start = 100;
    c.prune.every = 50;
    c.bounces = 0;
    c.farField.count = 2000;  // the paper's 75,000 is for scenes of millions of pixels
    return c;
  }
  static std::unique_ptr<Trainer> makeTrainer(const TrainConfig& c, bool black = false) {
    return set_->trainer(c, "fast", black);
  }

  static test::SmallTrainingSet* set_;
  static Dataset* dataset_;
  static TrainingViews* views_;
};

test::SmallTrainingSet* TrainerTest::set_ = nullptr;
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

// The photograph term as the only colour loss (no L_d, no L_r; black initial colours): its
// gradient reaches the first segment's diffuse and the reflected segments', so the error of
// diffuse + specular against the photographs falls. It starts with reflections. The same
// run with the term's weight 0 (the photographs still held, so the error is still reported)
// is the baseline. Measured: 0.193 against 0.246 after 150 steps with reflections.
TEST_F(TrainerTest, PhotographTermFitsDiffusePlusSpecularToThePhotographs) {
  const TrainingViews photographs =
      TrainingViews::load(*dataset_, dataset_->train(), ColourTarget::Diffuse, false, 0.1f, /*photograph=*/true);
  auto photographErrorAfterTraining = [&](float weight) {
    TrainConfig c = smallConfig();
    c.bounces = 1;
    c.reflectionWarmup = 50;
    c.loss = LossWeights{0, 2.5f, 2.5f, 1, 1, 0};
    c.loss.photograph = weight;
    c.lr.normal = c.lr.f0 = 0.02f;
    DenseInitSettings init;
    init.forceDepthBuffers = true;
    GaussianScene scene = denseInitialisation(*dataset_, init).scene;
    std::fill(scene.diffuse.begin(), scene.diffuse.end(), Rgb(0.0f));
    Trainer trainer(c, photographs, cameraSpheres(*dataset_, dataset_->train()), std::move(scene),
                    sceneExtent(dataset_->train()));
    double late = 0;
    for (int step = 1; step <= 200; ++step) {
      const StepReport r = trainer.step();
      if (step <= 50) {
        EXPECT_EQ(r.terms.photograph, 0.0) << "the term starts with reflections";
      }
      if (step > 150) late += r.terms.photograph / 50;
    }
    return late;
  };
  const double without = photographErrorAfterTraining(0.0f);
  const double with = photographErrorAfterTraining(3.0f);
  EXPECT_GT(without, 0.0);
  EXPECT_LT(with, 0.85 * without) << "with the term " << with << ", without " << without;
  std::printf("photograph L1 with the term %.4f, without %.4f\n", with, without);
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
  std::filesystem::copy(set_->folder.path(), copy.path(), std::filesystem::copy_options::recursive);
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

// Whole-image batches (TrainConfig::batchImages): every pixel of the step's views, in
// row-major order, each view once per epoch, the epochs in different seeded orders.
TEST_F(TrainerTest, WholeImageBatchesVisitEveryViewOncePerEpoch) {
  const size_t viewCount = views_->viewCount();  // 24: an epoch is 12 steps of 2 views
  std::vector<BatchRay> batch;
  std::vector<uint32_t> epochs[2];
  for (int64_t step = 0; step < int64_t(viewCount); ++step) {
    views_->drawWholeImages(7, step, 2, &batch);
    ASSERT_EQ(batch.size(), 2 * views_->pixelCount(0));
    for (size_t v = 0; v < 2; ++v) {
      const uint32_t view = batch[v * views_->pixelCount(0)].view;
      epochs[size_t(step) / (viewCount / 2)].push_back(view);
      for (size_t p = 0; p < views_->pixelCount(view); ++p) {
        const BatchRay& r = batch[v * views_->pixelCount(0) + p];
        ASSERT_EQ(r.view, view);
        ASSERT_EQ(r.pixel, p);
        const TraceRay expected = views_->pixelRay(view, p);
        ASSERT_EQ(r.ray.origin, expected.origin);
        ASSERT_EQ(r.ray.direction, expected.direction);
      }
    }
  }
  for (std::vector<uint32_t>& epoch : epochs) {
    std::vector<uint32_t> sorted = epoch;
    std::sort(sorted.begin(), sorted.end());
    for (size_t v = 0; v < viewCount; ++v) EXPECT_EQ(sorted[v], v) << "every view once per epoch";
  }
  EXPECT_NE(epochs[0], epochs[1]) << "each epoch in its own order";
  // The same (seed, step), the same batch; another seed, another order.
  std::vector<BatchRay> again, otherSeed;
  views_->drawWholeImages(7, 5, 2, &again);
  views_->drawWholeImages(8, 5, 2, &otherSeed);
  views_->drawWholeImages(7, 5, 2, &batch);
  EXPECT_EQ(again.front().view, batch.front().view);
  std::vector<uint32_t> order7, order8;
  for (int64_t step = 0; step < 12; ++step) {
    views_->drawWholeImages(7, step, 2, &batch);
    order7.push_back(batch.front().view);
    views_->drawWholeImages(8, step, 2, &batch);
    order8.push_back(batch.front().view);
  }
  EXPECT_NE(order7, order8);
  // More images than views: each step takes every view once.
  views_->drawWholeImages(7, 3, 1000, &batch);
  EXPECT_EQ(batch.size(), viewCount * views_->pixelCount(0));
}

// Training on whole images (camera rays in the tracer's bundles) improves the test views as
// random pixels do, prunes on the same scale, and is reproducible bit for bit across a resume.
TEST_F(TrainerTest, WholeImageTrainingImprovesTheTestViewsAndResumesBitExact) {
  TrainConfig c = smallConfig();
  c.batchImages = 1;  // 3,072 rays a step
  c.prune.start = 24;  // after each epoch of the 24 views
  c.prune.every = 24;
  std::unique_ptr<Trainer> straight = makeTrainer(c);
  const size_t initial = straight->scene().size();
  TestViews test = TestViews::load(*dataset_, dataset_->test(), 4);
  const TestScore before = test.score(straight->tracer(), 4);
  GaussianScene atStep60;
  for (int i = 0; i < 200; ++i) {
    const StepReport r = straight->step();
    ASSERT_EQ(r.rays, int64_t(views_->pixelCount(0)));
    EXPECT_EQ(r.overflowedRays, 0);
    if (i == 59) atStep60 = straight->scene();
  }
  const TestScore after = test.score(straight->tracer(), 4);
  EXPECT_GT(after.diffusePsnr, before.diffusePsnr + 5.0) << "before " << before.diffusePsnr;
  // Pruning scales a whole image's weight as random pixels' (Trainer::raysPerStep): the
  // same rays a step drawn at random pixels of one random view prune at least as many (a
  // view no step of an interval drew loses what only it sees; whole images see every view
  // each epoch). Weights scaled for 16,384 rays a step would prune most of the scene.
  TrainConfig random = c;
  random.batchImages = 0;
  random.batchRays = int(views_->pixelCount(0));
  random.batchViews = 1;
  std::unique_ptr<Trainer> randomPixels = makeTrainer(random);
  for (int i = 0; i < 200; ++i) randomPixels->step();
  EXPECT_LT(straight->scene().size(), initial);
  EXPECT_GE(straight->scene().size(), randomPixels->scene().size());

  std::unique_ptr<Trainer> first = makeTrainer(c);
  for (int i = 0; i < 30; ++i) first->step();
  test::TempFolder temp;
  writeCheckpoint(temp.path() / "state.bin", first->state());
  first.reset();
  Trainer resumed(c, *views_, cameraSpheres(*dataset_, dataset_->train()), readCheckpoint(temp.path() / "state.bin"));
  for (int i = 0; i < 30; ++i) resumed.step();
  const GaussianScene& b = resumed.scene();
  ASSERT_EQ(atStep60.size(), b.size());
  EXPECT_TRUE(sameTrainerBytes(atStep60.position, b.position));
  EXPECT_TRUE(sameTrainerBytes(atStep60.opacityLogit, b.opacityLogit));
  EXPECT_TRUE(sameTrainerBytes(atStep60.diffuse, b.diffuse));
}

// f0_tint_from_reflections learns the tint a metalness prior lacks. With an F0 prior (this
// set's F0 images, tinted already) L_r's F0 gradient is withheld, so the run is the run
// without the option, byte for byte; f0_from_specular alone does reach F0 there.
TEST_F(TrainerTest, TintOptionLeavesAnF0PriorToItsOwnTerm) {
  TrainConfig plain = smallConfig();
  plain.bounces = 1;
  plain.reflectionWarmup = 30;
  plain.lr.normal = plain.lr.f0 = 0.02f;  // valid normals (paths that reflect) within the warm-up
  TrainConfig tint = plain;
  tint.f0TintFromReflections = true;
  tint.loss.f0FromSpecular = 1;
  TrainConfig fromSpecular = plain;
  fromSpecular.loss.f0FromSpecular = 1;
  ASSERT_FALSE(views_->supervised().f0BrightnessOnly);
  auto trained = [&](const TrainConfig& c) {
    std::unique_ptr<Trainer> trainer = makeTrainer(c);
    for (int i = 0; i < 60; ++i) trainer->step();
    return trainer->scene();
  };
  const GaussianScene a = trained(plain), b = trained(tint), c = trained(fromSpecular);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(sameTrainerBytes(a.f0, b.f0));
  EXPECT_TRUE(sameTrainerBytes(a.position, b.position));
  EXPECT_TRUE(sameTrainerBytes(a.diffuse, b.diffuse));
  EXPECT_FALSE(a.size() == c.size() && sameTrainerBytes(a.f0, c.f0));
}

// The backward pass as a batch of jobs (what the GPU runs, raytrace/backward_batch.h), here
// on the CPU, summed hit by hit and by the GPU's own algorithm (records sorted by Gaussian):
// the jobs the trainer builds give its own gradients and split scores, bit for bit on one
// thread (the same sums in the same order), to rounding on two (the threads sum apart,
// then together), through reflected segments and weights, with L_r's gradient into
// roughness and F0 on (D15), which the jobs' adjoints carry.
TEST_F(TrainerTest, BackwardJobsGiveTheThreadsGradients) {
  TrainConfig c = smallConfig();
  c.bounces = 2;
  c.reflectionWarmup = 0;
  c.densify.start = 0;  // scores splits from the first step
  c.lr.normal = c.lr.f0 = 0.02f;  // valid normals soon, so that paths go on
  // Trained a little first, so that the blended normals are long enough for paths to go on.
  std::unique_ptr<Trainer> warm = makeTrainer(c);
  for (int i = 0; i < 60; ++i) warm->step();
  const TrainingState state = warm->state();
  c.loss.roughnessFromSpecular = 1.0f;
  c.loss.f0FromSpecular = 1.0f;
  {
    // The options reach roughness and F0: their gradients move well beyond rounding.
    TrainConfig off = c;
    off.loss.roughnessFromSpecular = off.loss.f0FromSpecular = 0.0f;
    Trainer with(c, *views_, cameraSpheres(*dataset_, dataset_->train()), state);
    Trainer without(off, *views_, cameraSpheres(*dataset_, dataset_->train()), state);
    std::vector<BatchRay> batch;
    views_->drawBatch(c.seed, 3, c.batchRays, c.batchViews, &batch);
    StepReport a, b;
    with.forwardBackward(batch, true, &a);
    without.forwardBackward(batch, true, &b);
    const GaussianGradients &on = with.lastGradient(), &detached = without.lastGradient();
    EXPECT_GT(test::relativeDifference(on.of(&GaussianScene::roughness), detached.of(&GaussianScene::roughness)), 0.01);
    EXPECT_GT(test::relativeDifference(on.of(&GaussianScene::f0), detached.of(&GaussianScene::f0)), 0.01);
  }
  const std::pair<GradientSum, int> runs[] = {
      {GradientSum::Atomic, 1}, {GradientSum::Atomic, 2}, {GradientSum::Sorted, 1}, {GradientSum::Sorted, 2}};
  for (const auto& [sum, threads] : runs) {
    SCOPED_TRACE(std::string(makeCpuBackwardBatch(sum)->name()) + ", " + std::to_string(threads) + " threads");
    ThreadLimit limit(threads);
    auto fromState = [&] {
      return std::make_unique<Trainer>(c, *views_, cameraSpheres(*dataset_, dataset_->train()), state);
    };
    std::unique_ptr<Trainer> own = fromState(), jobs = fromState();
    jobs->setBackwardBatch(makeCpuBackwardBatch(sum));
    std::vector<BatchRay> batch;
    views_->drawBatch(c.seed, 3, c.batchRays, c.batchViews, &batch);
    StepReport a, b;
    own->forwardBackward(batch, true, &a);
    jobs->forwardBackward(batch, true, &b);
    EXPECT_EQ(a.overflowedRays, b.overflowedRays);
    EXPECT_GT(a.reflectedSegments, 0);
    const GaussianGradients& ga = own->lastGradient();
    const GaussianGradients& gb = jobs->lastGradient();
    ASSERT_EQ(ga.size(), gb.size());
    using test::relativeDifference;
    for (size_t p = 0; p < ga.values.size(); ++p) {
      ASSERT_EQ(ga.values[p].size(), gb.values[p].size());
      if (threads == 1)
        EXPECT_TRUE(sameTrainerBytes(ga.values[p], gb.values[p])) << "parameter " << p;
      else
        EXPECT_LT(relativeDifference(gb.values[p], ga.values[p]), 1e-5) << "parameter " << p;
    }
    ASSERT_EQ(own->lastSplitScores().size(), ga.size());
    if (threads == 1) {
      EXPECT_TRUE(sameTrainerBytes(ga.weight, gb.weight));
      EXPECT_TRUE(sameTrainerBytes(own->lastSplitScores(), jobs->lastSplitScores()));
    } else {
      EXPECT_LT(relativeDifference(gb.weight, ga.weight), 1e-5);
      EXPECT_LT(relativeDifference(jobs->lastSplitScores(), own->lastSplitScores()), 1e-5);
    }
  }
}

// The depth band (LossWeights::depthBand) leaves out of the depth term the pixels whose
// rendered depth is far from their prior: a wide band keeps every one, a narrow one most
// of them out.
TEST_F(TrainerTest, DepthBandLeavesFarPixelsOutOfTheDepthTerm) {
  std::vector<BatchRay> batch;
  views_->drawBatch(0, 5, 2048, 2, &batch);
  auto depthTerm = [&](float band) {
    TrainConfig c = smallConfig();
    c.loss.depthBand = band;
    StepReport r;
    makeTrainer(c)->forwardBackward(batch, false, &r);
    return r.terms.depth;
  };
  const double all = depthTerm(0.0f);
  EXPECT_GT(all, 0.0);
  EXPECT_EQ(depthTerm(1e6f), all);
  EXPECT_LT(depthTerm(1e-4f), 0.2 * all);
}

// A path's result depends on its keys alone and each thread sums its lane in ray order, so
// the wavefronts' size (a GPU may want larger ones) does not change a step's bits.
TEST_F(TrainerTest, WavefrontSizeLeavesTheStepsAlone) {
  TrainConfig c = smallConfig();
  c.bounces = 1;
  c.reflectionWarmup = 2;
  std::unique_ptr<Trainer> usual = makeTrainer(c), small = makeTrainer(c);
  small->setWavefrontRays(700);
  for (int i = 0; i < 6; ++i) usual->step(), small->step();
  EXPECT_TRUE(sameTrainerBytes(usual->scene().position, small->scene().position));
  EXPECT_TRUE(sameTrainerBytes(usual->scene().diffuse, small->scene().diffuse));
  EXPECT_TRUE(sameTrainerBytes(usual->scene().opacityLogit, small->scene().opacityLogit));
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
