// The GPU's backward batch: the scene's parameters in GPU memory, one thread per job running
// backwardHits (raytrace/ray_backward.h, the CPU's own code), and each hit's gradient summed
// per Gaussian (raytrace/gradient_sums.h), either by atomic adds or through records sorted by
// Gaussian and summed in order (reproducible).
#include "cuda/cuda_backward.h"

#include <cuda_runtime.h>

#include <cub/device/device_radix_sort.cuh>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "cuda/cuda_check.h"
#include "cuda/device_buffer.h"
#include "cuda/launch.h"
#include "cuda/gpu_query.h"
#include "raytrace/gradient_sums.h"
#include "raytrace/ray_backward.h"

namespace glint {
namespace {

using cuda::blocksFor;
using cuda::kThreadsPerBlock;

// Sums each hit's gradient into its Gaussian's with atomic adds.
struct AtomicSink {
  GradientSums sums;
  GLINT_GPU void operator()(uint32_t id, const HitGradient<float>& g) const {
    forEachSum(sums, id, g, hitScore(sums, id, g), [](float* at, float value) { atomicAdd(at, value); });
  }
};

template <bool kRecord>
__global__ void backwardJobsKernel(BackwardScene scene, TraceSettings settings, const BackwardJob* jobs, uint32_t count,
                                   const HitRecord* hits, JobScratch scratch, GradientSums sums,
                                   HitGradient<float>* records, uint32_t* ids) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= count) return;
  const BackwardJob job = jobs[j];
  if constexpr (kRecord) {
    RecordSink sink{records, ids, job.firstHit};
    runBackwardJob(scene, settings, job, j, hits, scratch, sink);
  } else {
    AtomicSink sink{sums};
    runBackwardJob(scene, settings, job, j, hits, scratch, sink);
  }
}

// After the records are sorted by Gaussian: each run summed in order (sumSortedRun).
__global__ void sumSortedRunsKernel(const uint32_t* sortedIds, const uint32_t* sortedRecord,
                                    const HitGradient<float>* records, uint32_t count, GradientSums sums) {
  const uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r < count) sumSortedRun(sortedIds, sortedRecord, records, count, r, sums);
}

__global__ void sequenceKernel(uint32_t* values, uint32_t count) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < count) values[i] = i;
}

class CudaBackwardBatch final : public BackwardBatch {
 public:
  explicit CudaBackwardBatch(GradientSum sum) : sum_(sum) {
    std::string why;
    if (!cuda::queryGpu(&why)) throw Error("the GPU's backward pass cannot start: " + why);
  }

  const char* name() const override { return sum_ == GradientSum::Atomic ? "cuda (atomic sums)" : "cuda (sorted sums)"; }

  void begin(const GaussianScene& scene, const TraceSettings& settings, std::span<const float> sigmaMax) override {
    const char* what = "the Gaussians' parameters";
    n_ = scene.size();
    settings_ = settings;
    position_.upload(std::span<const Vec3f>(scene.position), what);
    rotation_.upload(std::span<const Quatf>(scene.rotation), what);
    logScale_.upload(std::span<const Vec3f>(scene.logScale), what);
    opacityLogit_.upload(std::span<const float>(scene.opacityLogit), what);
    diffuse_.upload(std::span<const Rgb>(scene.diffuse), what);
    normal_.upload(std::span<const Vec3f>(scene.normal), what);
    roughness_.upload(std::span<const float>(scene.roughness), what);
    f0_.upload(std::span<const Rgb>(scene.f0), what);
    scoring_ = !sigmaMax.empty();
    if (scoring_) sigmaMax_.upload(sigmaMax, "the Gaussians' sizes");
    // The sums, in one zeroed array (raytrace/gradient_sums.h).
    sums_.resize(n_ * kSumFloatsPerGaussian, "the Gaussians' gradients");
    cuda::check(cudaMemset(sums_.data(), 0, n_ * kSumFloatsPerGaussian * sizeof(float)), "clearing the gradients");
  }

  void add(std::span<const BackwardJob> jobs, std::span<const HitRecord> hits) override {
    if (jobs.empty()) return;
    GLINT_CHECK(jobs.size() < size_t(UINT32_MAX) && hits.size() + jobs.size() < size_t(UINT32_MAX),
                "a backward batch of more than 4 billion hits");
    const char* what = "a batch of backward jobs";
    const uint32_t count = uint32_t(jobs.size()), hitCount = uint32_t(hits.size());
    jobs_.upload(jobs, what);
    hits_.upload(hits, what);
    transmittance_.resize(size_t(hitCount) + count, what);
    alpha_.resize(std::max<size_t>(hitCount, 1), what);
    key_.resize(std::max<size_t>(hitCount, 1), what);
    const JobScratch scratch{transmittance_.data(), alpha_.data(), key_.data()};
    const GradientSums sums = GradientSums::in(sums_.data(), n_, scoring_ ? sigmaMax_.data() : nullptr);
    const BackwardScene scene{{position_.data(), rotation_.data(), logScale_.data(), opacityLogit_.data()},
                              {diffuse_.data(), normal_.data(), roughness_.data(), f0_.data()}};
    if (sum_ == GradientSum::Atomic) {
      backwardJobsKernel<false><<<blocksFor(count), kThreadsPerBlock>>>(scene, settings_, jobs_.data(), count,
                                                                        hits_.data(), scratch, sums, nullptr, nullptr);
      cuda::checkLaunch("the backward pass");
      return;
    }
    if (hitCount == 0) return;
    records_.resize(hitCount, what);
    ids_[0].resize(hitCount, what);
    ids_[1].resize(hitCount, what);
    recordIndex_[0].resize(hitCount, what);
    recordIndex_[1].resize(hitCount, what);
    backwardJobsKernel<true><<<blocksFor(count), kThreadsPerBlock>>>(scene, settings_, jobs_.data(), count, hits_.data(),
                                                                     scratch, sums, records_.data(), ids_[0].data());
    cuda::check(cudaGetLastError(), "the backward pass");
    sequenceKernel<<<blocksFor(hitCount), kThreadsPerBlock>>>(recordIndex_[0].data(), hitCount);
    cuda::check(cudaGetLastError(), "the backward pass");
    // Radix sort is stable: records of one Gaussian keep their (job) order.
    int bits = 1;
    while (bits < 32 && (uint64_t(1) << bits) < n_) ++bits;
    size_t tempBytes = 0;
    cuda::check(cub::DeviceRadixSort::SortPairs(nullptr, tempBytes, ids_[0].data(), ids_[1].data(),
                                                recordIndex_[0].data(), recordIndex_[1].data(), int(hitCount), 0, bits),
                "sorting the gradients by Gaussian");
    sortTemp_.resize(std::max<size_t>(tempBytes, 1), "sorting the gradients by Gaussian");
    cuda::check(cub::DeviceRadixSort::SortPairs(sortTemp_.data(), tempBytes, ids_[0].data(), ids_[1].data(),
                                                recordIndex_[0].data(), recordIndex_[1].data(), int(hitCount), 0, bits),
                "sorting the gradients by Gaussian");
    sumSortedRunsKernel<<<blocksFor(hitCount), kThreadsPerBlock>>>(ids_[1].data(), recordIndex_[1].data(),
                                                                   records_.data(), hitCount, sums);
    cuda::checkLaunch("summing the gradients by Gaussian");
  }

  void finish(GaussianGradients* gradient, std::vector<float>* splitScore) override {
    std::vector<float> host(n_ * kSumFloatsPerGaussian);
    sums_.download(host, "downloading the gradients");
    copySums(host, n_, scoring_, gradient, splitScore);
  }

 private:
  GradientSum sum_;
  size_t n_ = 0;
  TraceSettings settings_;
  bool scoring_ = false;
  cuda::DeviceBuffer<Vec3f> position_, logScale_, normal_;
  cuda::DeviceBuffer<Quatf> rotation_;
  cuda::DeviceBuffer<float> opacityLogit_, roughness_, sigmaMax_;
  cuda::DeviceBuffer<Rgb> diffuse_, f0_;
  cuda::DeviceBuffer<float> sums_;
  cuda::DeviceBuffer<BackwardJob> jobs_;
  cuda::DeviceBuffer<HitRecord> hits_;
  cuda::DeviceBuffer<float> transmittance_, alpha_, key_;
  cuda::DeviceBuffer<HitGradient<float>> records_;
  cuda::DeviceBuffer<uint32_t> ids_[2], recordIndex_[2];
  cuda::DeviceBuffer<unsigned char> sortTemp_;
};

}  // namespace

std::unique_ptr<BackwardBatch> makeCudaBackwardBatch(GradientSum sum) { return std::make_unique<CudaBackwardBatch>(sum); }

}  // namespace glint
