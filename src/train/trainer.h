// The training step (paper sections 3.1-3.3, appendix A): each step draws a batch of rays,
// traces their paths as one wavefront, runs the losses and the backward pass per path, reduces the
// per-thread gradients, takes an Adam step, applies the schedule (scale decay, clamping,
// pruning, camera-sphere culling) and refits or rebuilds the tracer.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include "raytrace/backward_batch.h"
#include "raytrace/gaussian_gradients.h"
#include "raytrace/gaussian_tracer.h"
#include "raytrace/ray_backward.h"
#include "render/gaussian_path.h"
#include "train/adam.h"
#include "train/camera_culling.h"
#include "train/checkpoint.h"
#include "train/gradient_exchange.h"
#include "train/ray_loss.h"
#include "train/train_config.h"
#include "train/training_views.h"

namespace glint {

struct StepReport {
  int64_t step = 0;          // steps completed after this one
  LossTerms terms;           // unweighted mean errors of the batch
  double loss = 0;           // weighted total
  size_t gaussians = 0;      // after housekeeping
  int64_t rays = 0;
  int64_t hits = 0;          // composited hits over the batch
  int64_t reflectedSegments = 0;  // traced after first segments (0 before reflections start)
  int64_t overflowedRays = 0;  // rays whose hit list overflowed (no gradient; never expected)
  size_t pruned = 0;         // removed this step (weight pruning and camera spheres)
  size_t split = 0;          // Gaussians split in two this step (train/densify.h)
  size_t farFieldAdded = 0;  // far-field Gaussians added before this step (when reflections start)
  size_t reflectionSeedsAdded = 0;  // of them, seeded along mirror reflections (train/reflection_seeds.h)
  double seconds = 0;        // wall time of the step
  // Its parts (bench/cluster_bench): tracing the wavefronts, their losses and backward pass
  // with the reduction of the threads' sums, the exchange between the ranks of an MPI job,
  // and the Adam step with the clamping after it; in an MPI job also the wait for the
  // slowest rank before the exchange (the imbalance of the shares).
  double traceSeconds = 0, backwardSeconds = 0, waitSeconds = 0, exchangeSeconds = 0, adamSeconds = 0;
  // Of backwardSeconds, the reduction: the threads' buffers summed, or the GPU's sums
  // downloaded (its kernels run while the host goes on, so their time shows here).
  double reduceSeconds = 0;
  // Pruning, densification and the tracer's refit or rebuild after the update.
  double housekeepingSeconds = 0;
  uint64_t exchangedBytes = 0;  // received by this rank in the exchange
  bool sparseExchange = false;  // the exchange sent the touched Gaussians only
  // The roughness priors' offset from the model: the median of prior - model roughness
  // over the batch's surface pixels (0 without roughness priors). With
  // TrainConfig::roughnessShiftInvariant the next step's roughness term takes it out.
  float roughnessOffset = 0;

  // Adds the other step's times (the whole step's and each part's), for benchmarks that sum steps.
  void addTimes(const StepReport& o) {
    seconds += o.seconds;
    traceSeconds += o.traceSeconds, backwardSeconds += o.backwardSeconds, waitSeconds += o.waitSeconds;
    exchangeSeconds += o.exchangeSeconds, adamSeconds += o.adamSeconds, reduceSeconds += o.reduceSeconds;
    housekeepingSeconds += o.housekeepingSeconds;
  }
};

class Trainer {
 public:
  // Paths per wavefront of a step: a batch is traced and back-propagated in wavefronts of
  // at most this many paths, so the records (hit lists of every segment, about 6 KB per
  // path) stay bounded whatever the batch size.
  static constexpr int64_t kWavefrontRays = 8192;

  // Paths per wavefront (kWavefrontRays unless set): a GPU may want larger ones, each level
  // of a wavefront being a round trip to it (train_bench --wavefront-rays measures).
  void setWavefrontRays(int64_t paths);
  int64_t wavefrontRays() const { return wavefrontRays_; }

  // Starts from `initial` (the dense initialisation) at step 0. The views and spheres
  // are referenced and must outlive the trainer. Gaussians inside the camera spheres are
  // removed at once.
  Trainer(const TrainConfig& config, const TrainingViews& views, std::vector<CameraSphere> spheres,
          GaussianScene initial, float sceneExtent, const std::string& tracerKind = "fast");
  // Continues from a checkpoint's state (its config must be the one given).
  Trainer(const TrainConfig& config, const TrainingViews& views, std::vector<CameraSphere> spheres,
          TrainingState state, const std::string& tracerKind = "fast");
  ~Trainer();

  StepReport step();

  // The fused forward/backward pass of a batch into the per-thread gradient buffers,
  // reduced into one, without an update (step() = drawBatch + this + Adam + schedule).
  // With backward false only the forward pass and the loss run (benchmarks compare the two).
  void forwardBackward(std::span<const BatchRay> batch, bool backward, StepReport* report);

  // Where the backward pass runs: by default on the CPU's threads, or (set up with a GPU
  // tracer) the GPU's BackwardBatch; tests and benchmarks may give another (null: the CPU's
  // threads).
  void setBackwardBatch(std::unique_ptr<BackwardBatch> batch);
  const BackwardBatch* backwardBatch() const { return backwardBatch_.get(); }
  // The gradients of the last forwardBackward (or step), summed over the batch, and, when
  // that pass scored splits, the densification scores.
  const GaussianGradients& lastGradient() const;
  const std::vector<float>& lastSplitScores() const;

  int64_t stepCount() const { return step_; }
  const GaussianScene& scene() const { return scene_; }
  float sceneExtent() const { return extent_; }
  // How an MPI job exchanges its gradients (train/gradient_exchange.h).
  void setExchangeMode(ExchangeMode mode) { exchangeMode_ = mode; }
  // The tracer over the current scene (built with the training settings), for evaluation.
  const GaussianTracer& tracer() const { return *tracer_; }
  TrainingState state() const;
  // Bytes of the forward pass's wavefront (records and hit lists of the last batch).
  size_t wavefrontBytes() const { return pathBatch_.memoryBytes(); }

 private:
  struct Slot;  // per-thread scratch and gradient buffer

  void setUp(const std::string& tracerKind);
  // Pruning, densification, and the tracer's refit or rebuild; fills report->pruned and
  // report->split.
  void housekeeping(StepReport* report);
  // Splits the Gaussians of highest densification score (train/densify.h); returns how many.
  size_t densify();
  size_t prune();  // weight pruning and camera-sphere culling; returns how many went
  // Gathers the slots' backward jobs of a wavefront and hands them to `device`.
  void handToDevice(BackwardBatch* device);
  // Rays a step traces: batchRays, or the mean pixel count of batchImages whole views.
  double raysPerStep() const;
  // Whether this step's backward pass accumulates the densification score.
  bool scoringSplits() const;
  // Appends the far-field Gaussians outside the camera spheres and the reflection seeds;
  // returns how many of each.
  std::pair<size_t, size_t> addFarField();

  TrainConfig config_;
  const TrainingViews& views_;
  std::vector<CameraSphere> spheres_;
  ExchangeMode exchangeMode_ = ExchangeMode::Dense;
  GaussianScene scene_;
  float extent_ = 1;
  int64_t step_ = 0;
  AdamOptimizer adam_;
  std::vector<float> pruneWeight_;
  std::vector<float> densifyScore_;  // split score accumulated since the last densify step
  // The last step's roughness offset, taken out of the priors when roughnessShiftInvariant
  // (0 otherwise).
  float roughnessShift_ = 0;
  std::vector<float> sigmaMax_;      // largest standard deviation per Gaussian, for the score
  std::unique_ptr<GaussianTracer> tracer_;
  std::vector<std::unique_ptr<Slot>> slots_;
  std::vector<BatchRay> batch_;
  // The forward pass's wavefront and its inputs and outputs, kept between steps.
  PathBatch pathBatch_;
  std::vector<TraceRay> rays_;
  std::vector<PathKey> keys_;
  std::vector<PathResult> paths_;
  int64_t wavefrontRays_ = kWavefrontRays;
  std::unique_ptr<BackwardBatch> backwardBatch_;  // null: the backward pass on the CPU's threads
  std::vector<BackwardJob> deviceJobs_;           // a wavefront's jobs for it, and their hits
  std::vector<HitRecord> deviceHits_;
};

}  // namespace glint
