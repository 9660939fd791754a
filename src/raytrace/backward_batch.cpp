// The CPU's backward batch: the jobs in order, each through backwardHits, into one buffer.
#include "raytrace/backward_batch.h"

#include "core/error.h"

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

}  // namespace

std::unique_ptr<BackwardBatch> makeCpuBackwardBatch() { return std::make_unique<CpuBackwardBatch>(); }

}  // namespace glint
