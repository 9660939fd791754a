// The CPU's backward batches: the jobs in order into one buffer, or the GPU's algorithm run on
// the CPU (records, a stable sort by Gaussian, runs summed in order).
#include "raytrace/backward_batch.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/gradient_sums.h"

namespace glint {
namespace {

class CpuBackwardBatch final : public BackwardBatch {
 public:
  const char* name() const override { return "cpu"; }

  void begin(const GaussianScene& scene, const TraceSettings& settings, std::span<const float> sigmaMax) override {
    scene_ = &scene;
    settings_ = settings;
    gradient_.reset(scene.size());
    scoring_ = !sigmaMax.empty();
    sigmaMax_.assign(sigmaMax.begin(), sigmaMax.end());
    score_.assign(scoring_ ? scene.size() : 0, 0.0f);
  }

  void add(std::span<const BackwardJob> jobs, std::span<const HitRecord> hits) override {
    GLINT_CHECK(scene_, "BackwardBatch::add before begin");
    const BackwardScene scene = BackwardScene::of(*scene_);
    auto sink = [&](uint32_t id, const HitGradient<float>& g) {
      gradient_.add(id, g);
      if (scoring_) score_[id] += splitScore(g, sigmaMax_[id]);
    };
    for (const BackwardJob& job : jobs) {
      GLINT_CHECK(size_t(job.firstHit) + job.hitCount <= hits.size(), "a backward job's hits lie outside the batch");
      const size_t n = job.hitCount;
      scratch_.transmittance.resize(n + 1);
      scratch_.alpha.resize(n);
      scratch_.key.resize(n);
      backwardHits<float>(scene, settings_, job.ray, hits.data() + job.firstHit, n, job.truncated, job.transmittance,
                          job.v, scratch_.transmittance.data(), scratch_.alpha.data(), scratch_.key.data(), sink);
    }
  }

  void finish(GaussianGradients* gradient, std::vector<float>* splitScore) override {
    *gradient = std::move(gradient_);
    if (splitScore) *splitScore = std::move(score_);
    gradient_ = {};
    score_.clear();
    scene_ = nullptr;
  }

 private:
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  bool scoring_ = false;
  std::vector<float> sigmaMax_;
  GaussianGradients gradient_;
  std::vector<float> score_;
  RayBackwardScratch<float> scratch_;
};

// The GPU's sorted sums (cuda/cuda_backward.cu) step by step on the CPU, with the same
// GLINT_CPU_GPU code (raytrace/gradient_sums.h): each job's gradients recorded at its hits'
// places, the records sorted stably by Gaussian (std::stable_sort for CUB's radix sort), and
// each Gaussian's run summed in order into the flat sums.
class EmulatedGpuBackwardBatch final : public BackwardBatch {
 public:
  const char* name() const override { return "cpu (the GPU's sorted sums)"; }

  void begin(const GaussianScene& scene, const TraceSettings& settings, std::span<const float> sigmaMax) override {
    scene_ = &scene;
    settings_ = settings;
    n_ = scene.size();
    scoring_ = !sigmaMax.empty();
    sigmaMax_.assign(sigmaMax.begin(), sigmaMax.end());
    sums_.assign(n_ * kSumFloatsPerGaussian, 0.0f);
  }

  void add(std::span<const BackwardJob> jobs, std::span<const HitRecord> hits) override {
    GLINT_CHECK(scene_, "BackwardBatch::add before begin");
    if (jobs.empty()) return;
    const BackwardScene scene = BackwardScene::of(*scene_);
    const uint32_t hitCount = uint32_t(hits.size());
    records_.resize(hitCount);
    ids_.resize(hitCount);
    transmittance_.resize(hits.size() + jobs.size());
    alpha_.resize(hits.size());
    key_.resize(hits.size());
    const JobScratch scratch{transmittance_.data(), alpha_.data(), key_.data()};
    // The kernel's threads: one job each.
    parallelFor(int64_t(jobs.size()), 64, [&](int64_t j) {
      const BackwardJob& job = jobs[size_t(j)];
      GLINT_CHECK(size_t(job.firstHit) + job.hitCount <= hits.size(), "a backward job's hits lie outside the batch");
      RecordSink sink{records_.data(), ids_.data(), job.firstHit};
      runBackwardJob(scene, settings_, job, uint32_t(j), hits.data(), scratch, sink);
    });
    order_.resize(hitCount);
    std::iota(order_.begin(), order_.end(), 0u);
    std::stable_sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) { return ids_[a] < ids_[b]; });
    sortedIds_.resize(hitCount);
    for (uint32_t r = 0; r < hitCount; ++r) sortedIds_[r] = ids_[order_[r]];
    const GradientSums sums = GradientSums::in(sums_.data(), n_, scoring_ ? sigmaMax_.data() : nullptr);
    // The reduction kernel's threads: one position each, the first of each run summing it.
    parallelFor(int64_t(hitCount), 1024, [&](int64_t r) {
      sumSortedRun(sortedIds_.data(), order_.data(), records_.data(), hitCount, uint32_t(r), sums);
    });
  }

  void finish(GaussianGradients* gradient, std::vector<float>* splitScore) override {
    copySums(sums_, n_, scoring_, gradient, splitScore);
    scene_ = nullptr;
  }

 private:
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  size_t n_ = 0;
  bool scoring_ = false;
  std::vector<float> sigmaMax_, sums_;
  std::vector<HitGradient<float>> records_;
  std::vector<uint32_t> ids_, order_, sortedIds_;
  std::vector<float> transmittance_, alpha_, key_;
};

}  // namespace

std::unique_ptr<BackwardBatch> makeCpuBackwardBatch(GradientSum sum) {
  if (sum == GradientSum::Sorted) return std::make_unique<EmulatedGpuBackwardBatch>();
  return std::make_unique<CpuBackwardBatch>();
}

}  // namespace glint
