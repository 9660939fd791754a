// The CPU's backward batch: the GPU's code (raytrace/gradient_sums.h) run on the CPU, one loop
// iteration per GPU thread, summing hit by hit in job order or through records sorted by
// Gaussian.
#include "raytrace/backward_batch.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/gradient_sums.h"

namespace glint {
namespace {

// Atomic: each job's gradients added as they come, the jobs in order on the calling thread
// (the order atomic adds take when the GPU's threads arrive in job order). Sorted: the GPU's
// steps, each job's gradients recorded at its hits' places (jobs in parallel), the records
// sorted stably by Gaussian (std::stable_sort for CUB's radix sort), each Gaussian's run
// summed in order.
class CpuBackwardBatch final : public BackwardBatch {
 public:
  explicit CpuBackwardBatch(GradientSum sum) : sum_(sum) {}

  const char* name() const override { return sum_ == GradientSum::Sorted ? "cpu (the GPU's sorted sums)" : "cpu"; }

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
    for (const BackwardJob& job : jobs)
      GLINT_CHECK(size_t(job.firstHit) + job.hitCount <= hits.size(), "a backward job's hits lie outside the batch");
    const BackwardScene scene = BackwardScene::of(*scene_);
    const uint32_t hitCount = uint32_t(hits.size());
    transmittance_.resize(hits.size() + jobs.size());
    alpha_.resize(hits.size());
    key_.resize(hits.size());
    const JobScratch scratch{transmittance_.data(), alpha_.data(), key_.data()};
    const GradientSums sums = GradientSums::in(sums_.data(), n_, scoring_ ? sigmaMax_.data() : nullptr);
    if (sum_ == GradientSum::Atomic) {
      auto sink = [&](uint32_t id, const HitGradient<float>& g) {
        forEachSum(sums, id, g, hitScore(sums, id, g), [](float* at, float value) { *at += value; });
      };
      for (uint32_t j = 0; j < uint32_t(jobs.size()); ++j)
        runBackwardJob(scene, settings_, jobs[j], j, hits.data(), scratch, sink);
      return;
    }
    records_.resize(hitCount);
    ids_.resize(hitCount);
    parallelFor(int64_t(jobs.size()), 64, [&](int64_t j) {
      RecordSink sink{records_.data(), ids_.data(), jobs[size_t(j)].firstHit};
      runBackwardJob(scene, settings_, jobs[size_t(j)], uint32_t(j), hits.data(), scratch, sink);
    });
    order_.resize(hitCount);
    std::iota(order_.begin(), order_.end(), 0u);
    std::stable_sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) { return ids_[a] < ids_[b]; });
    sortedIds_.resize(hitCount);
    for (uint32_t r = 0; r < hitCount; ++r) sortedIds_[r] = ids_[order_[r]];
    // One position each, the first of each run summing it (so no two write one Gaussian).
    parallelFor(int64_t(hitCount), 1024, [&](int64_t r) {
      sumSortedRun(sortedIds_.data(), order_.data(), records_.data(), hitCount, uint32_t(r), sums);
    });
  }

  void finish(GaussianGradients* gradient, std::vector<float>* splitScore) override {
    copySums(sums_, n_, scoring_, gradient, splitScore);
    scene_ = nullptr;
  }

 private:
  GradientSum sum_;
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  size_t n_ = 0;
  bool scoring_ = false;
  std::vector<float> sigmaMax_, sums_;
  std::vector<float> transmittance_, alpha_, key_;
  std::vector<HitGradient<float>> records_;
  std::vector<uint32_t> ids_, order_, sortedIds_;
};

}  // namespace

std::unique_ptr<BackwardBatch> makeCpuBackwardBatch(GradientSum sum) { return std::make_unique<CpuBackwardBatch>(sum); }

}  // namespace glint
