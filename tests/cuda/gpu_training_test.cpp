// Training on the GPU against the CPU (issue 42): one batch's gradients agree per parameter
// array, the GPU's sorted sums are reproducible bit for bit, and 500 steps on each device
// score alike on the test views. Part of test_cuda, which exits 77 (skipped) where no GPU is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "common/relative_difference.h"
#include "common/small_training_set.h"
#include "eval/image_metrics.h"
#include "raytrace/backward_batch.h"
#include "render/gaussian_renderer.h"
#include "train/trainer.h"

namespace glint {
namespace {

class GpuTraining : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    set_ = test::SmallTrainingSet::make().release();
    dataset_ = set_->dataset.get();
    views_ = set_->views.get();
  }
  static void TearDownTestSuite() { delete set_; }
  static TrainConfig config() {
    TrainConfig c;
    c.dataset = set_->folder.path().string();
    c.batchRays = 2048;
    c.batchViews = 2;
    c.bounces = 2;
    c.reflectionWarmup = 0;
    c.lr.normal = c.lr.f0 = 0.02f;  // valid normals soon, so that paths go on
    c.prune.start = 100;
    c.prune.every = 50;
    c.densify.start = 0;  // scores splits from the first step
    c.densify.every = 100;
    c.farField.count = 2000;
    return c;
  }
  static std::unique_ptr<Trainer> fromScratch(const TrainConfig& c, const char* tracer) {
    return set_->trainer(c, tracer);
  }
  static std::unique_ptr<Trainer> fromState(const TrainConfig& c, const TrainingState& state, const char* tracer) {
    return set_->resumed(c, state, tracer);
  }

  static test::SmallTrainingSet* set_;
  static Dataset* dataset_;
  static TrainingViews* views_;
};

test::SmallTrainingSet* GpuTraining::set_ = nullptr;
Dataset* GpuTraining::dataset_ = nullptr;
TrainingViews* GpuTraining::views_ = nullptr;

using test::relativeDifference;

// A state 60 steps in, where the blended normals let paths go on.
TrainingState warmState() {
  static const TrainingState state = [] {
    std::unique_ptr<Trainer> warm = GpuTraining::fromScratch(GpuTraining::config(), "fast");
    for (int i = 0; i < 60; ++i) warm->step();
    return warm->state();
  }();
  return state;
}

// The same batch through the CPU's trainer and the GPU's (its tracer and its backward batch,
// both ways of summing): every parameter array's gradient within 1e-3 of the CPU's (relative,
// in the L2 norm: single elements may differ more where the sums cancel), the weights and
// split scores likewise. The hit lists are the CPU's bit for bit (gpu_vs_cpu_test), so the
// differences are the sums' order and the reflected directions' sin and cos.
TEST_F(GpuTraining, OneBatchsGradientsAgreeWithTheCpus) {
  const TrainConfig c = config();
  const TrainingState state = warmState();
  std::vector<BatchRay> batch;
  views_->drawBatch(c.seed, 1000, c.batchRays, c.batchViews, &batch);
  std::unique_ptr<Trainer> cpu = fromState(c, state, "fast");
  StepReport cpuReport;
  cpu->forwardBackward(batch, true, &cpuReport);
  ASSERT_GT(cpuReport.reflectedSegments, 0);
  for (GradientSum sum : {GradientSum::Sorted, GradientSum::Atomic}) {
    std::unique_ptr<Trainer> gpu = fromState(c, state, "cuda");
    gpu->setBackwardBatch(makeBackwardBatch("cuda", sum));
    ASSERT_NE(gpu->backwardBatch(), nullptr);
    StepReport gpuReport;
    gpu->forwardBackward(batch, true, &gpuReport);
    EXPECT_EQ(gpuReport.hits, cpuReport.hits);
    EXPECT_EQ(gpuReport.overflowedRays, cpuReport.overflowedRays);
    const GaussianGradients& a = gpu->lastGradient();
    const GaussianGradients& b = cpu->lastGradient();
    ASSERT_EQ(a.size(), b.size());
    for (size_t p = 0; p < a.values.size(); ++p) {
      const double d = relativeDifference(a.values[p], b.values[p]);
      std::printf("%s: parameter %zu relative difference %.3g\n", gpu->backwardBatch()->name(), p, d);
      EXPECT_LE(d, 1e-3) << "parameter " << p;
    }
    EXPECT_LE(relativeDifference(a.weight, b.weight), 1e-3);
    EXPECT_LE(relativeDifference(gpu->lastSplitScores(), cpu->lastSplitScores()), 1e-3);
  }
}

// Sorted sums (the default) give the same bits on every run; so does a GPU run.
TEST_F(GpuTraining, SortedSumsAreReproducible) {
  const TrainConfig c = config();
  const TrainingState state = warmState();
  std::vector<BatchRay> batch;
  views_->drawBatch(c.seed, 1001, c.batchRays, c.batchViews, &batch);
  std::unique_ptr<Trainer> first = fromState(c, state, "cuda"), second = fromState(c, state, "cuda");
  StepReport r1, r2;
  first->forwardBackward(batch, true, &r1);
  second->forwardBackward(batch, true, &r2);
  for (size_t p = 0; p < first->lastGradient().values.size(); ++p) {
    const std::vector<float>& a = first->lastGradient().values[p];
    const std::vector<float>& b = second->lastGradient().values[p];
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "parameter " << p;
  }
  for (int i = 0; i < 20; ++i) first->step(), second->step();
  const std::vector<Vec3f>& a = first->scene().position;
  const std::vector<Vec3f>& b = second->scene().position;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3f)), 0);
}

// The test views' diffuse and specular PSNR (tonemapped 8-bit, mean over views) of a trained
// scene, rendered with 16 samples and the run's paths on the CPU.
std::pair<double, double> testScores(const GaussianScene& scene, const TrainConfig& c, const Dataset& dataset) {
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, c.trace);
  RenderSettings settings;
  settings.spp = 16;
  settings.path = c.renderPath();
  double diffuse = 0, specular = 0;
  const DatasetSplit& split = dataset.test();
  for (size_t v = 0; v < split.views.size(); ++v) {
    const ViewBuffers ours = renderGaussianView(*tracer, split.camera(v), settings, v);
    diffuse += psnrTonemapped8Bit(ours[Buffer::Diffuse], dataset.loadBuffer(split, v, Buffer::Diffuse));
    specular += psnrTonemapped8Bit(ours[Buffer::Specular], dataset.loadBuffer(split, v, Buffer::Specular));
  }
  return {diffuse / double(split.views.size()), specular / double(split.views.size())};
}

// 500 steps from the same start on each device score within 0.3 dB of each other on the test
// views (diffuse and specular, rendered alike on the CPU), and the GPU's checkpoint goes on
// on the CPU.
TEST_F(GpuTraining, FiveHundredStepsScoreAsOnTheCpu) {
  const TrainConfig c = config();
  std::pair<double, double> scores[2];
  const char* tracers[2] = {"fast", "cuda"};
  std::unique_ptr<Trainer> gpu;
  for (int d = 0; d < 2; ++d) {
    std::unique_ptr<Trainer> t = fromScratch(c, tracers[d]);
    for (int i = 0; i < 500; ++i) t->step();
    scores[d] = testScores(t->scene(), c, *dataset_);
    std::printf("%s: 500 steps, %zu Gaussians, diffuse %.2f dB, specular %.2f dB\n", tracers[d], t->scene().size(),
                scores[d].first, scores[d].second);
    if (d == 1) gpu = std::move(t);
  }
  EXPECT_NEAR(scores[1].first, scores[0].first, 0.3);
  EXPECT_NEAR(scores[1].second, scores[0].second, 0.3);
  std::unique_ptr<Trainer> resumed = fromState(c, gpu->state(), "fast");
  const StepReport r = resumed->step();
  EXPECT_EQ(r.step, 501);
  EXPECT_TRUE(std::isfinite(r.loss));
}

}  // namespace
}  // namespace glint
