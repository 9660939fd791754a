// The GPU's backward batch: the scene's parameters in GPU memory, one thread per job running
// backwardHits (raytrace/ray_backward.h, the CPU's own code), and each hit's gradient summed
// per Gaussian, either by atomic adds or through records sorted by Gaussian and summed in
// order (reproducible).
#include "cuda/cuda_backward.h"

#include <cuda_runtime.h>

#include <cub/device/device_radix_sort.cuh>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "cuda/cuda_check.h"
#include "cuda/device_buffer.h"
#include "cuda/gpu_query.h"
#include "raytrace/ray_backward.h"

namespace glint {
namespace {

constexpr int kThreadsPerBlock = 128;

unsigned blocksFor(size_t n) { return unsigned((n + kThreadsPerBlock - 1) / kThreadsPerBlock); }

// The per-Gaussian sums in GPU memory, one array per parameter in GaussianGradients' layout
// (Gaussian i's components at [i * components, (i + 1) * components), a quaternion's as w,
// x, y, z), the blend weight and, when sigmaMax is given, the densification score.
struct DeviceSums {
  float *position, *rotation, *logScale, *opacityLogit, *diffuse, *normal, *roughness, *f0, *weight, *score;
  const float* sigmaMax;  // null: no scores
};

// Calls add(address, value) for every float of one hit's gradient (and its score).
template <typename Add>
GLINT_GPU void forEachSum(const DeviceSums& s, uint32_t id, const HitGradient<float>& g, float score, Add add) {
  const Vec3f* vectors[5] = {&g.v_position, &g.v_logScale, &g.v_diffuse, &g.v_normal, &g.v_f0};
  float* arrays[5] = {s.position, s.logScale, s.diffuse, s.normal, s.f0};
  GLINT_UNROLL
  for (int a = 0; a < 5; ++a) {
    add(arrays[a] + 3 * size_t(id) + 0, vectors[a]->x);
    add(arrays[a] + 3 * size_t(id) + 1, vectors[a]->y);
    add(arrays[a] + 3 * size_t(id) + 2, vectors[a]->z);
  }
  add(s.rotation + 4 * size_t(id) + 0, g.v_rotation.w);
  add(s.rotation + 4 * size_t(id) + 1, g.v_rotation.x);
  add(s.rotation + 4 * size_t(id) + 2, g.v_rotation.y);
  add(s.rotation + 4 * size_t(id) + 3, g.v_rotation.z);
  add(s.opacityLogit + id, g.v_opacityLogit);
  add(s.roughness + id, g.v_roughness);
  add(s.weight + id, g.weight);
  if (s.sigmaMax) add(s.score + id, score);
}

// Sums each hit's gradient into its Gaussian's with atomic adds.
struct AtomicSink {
  DeviceSums sums;
  GLINT_GPU void operator()(uint32_t id, const HitGradient<float>& g) const {
    const float score = sums.sigmaMax ? splitScore(g, sums.sigmaMax[id]) : 0.0f;
    forEachSum(sums, id, g, score, [](float* at, float value) { atomicAdd(at, value); });
  }
};

// Records each hit's gradient and Gaussian at the job's next record (a job's records are its
// hits' places in the batch: the k-th gradient it hands out goes to firstHit + k).
struct RecordSink {
  HitGradient<float>* records;
  uint32_t* ids;
  uint32_t next;
  GLINT_GPU void operator()(uint32_t id, const HitGradient<float>& g) {
    records[next] = g;
    ids[next] = id;
    ++next;
  }
};

// Scratch of the jobs: job j's transmittances at [firstHit + j, firstHit + j + hitCount + 1),
// its alphas and keys at [firstHit, firstHit + hitCount).
struct JobScratch {
  float *transmittance, *alpha, *key;
};

template <bool kRecord>
__global__ void backwardJobsKernel(BackwardScene scene, TraceSettings settings, const BackwardJob* jobs, uint32_t count,
                                   const HitRecord* hits, JobScratch scratch, DeviceSums sums,
                                   HitGradient<float>* records, uint32_t* ids) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= count) return;
  const BackwardJob job = jobs[j];
  float* trans = scratch.transmittance + job.firstHit + j;
  float* alpha = scratch.alpha + job.firstHit;
  float* key = scratch.key + job.firstHit;
  if constexpr (kRecord) {
    RecordSink sink{records, ids, job.firstHit};
    backwardHits<float>(scene, settings, job.ray, hits + job.firstHit, job.hitCount, job.truncated, job.transmittance,
                        job.v, trans, alpha, key, sink);
  } else {
    AtomicSink sink{sums};
    backwardHits<float>(scene, settings, job.ray, hits + job.firstHit, job.hitCount, job.truncated, job.transmittance,
                        job.v, trans, alpha, key, sink);
  }
}

// After the records are sorted by Gaussian (stably, so each Gaussian's in job order): the
// thread at the start of each Gaussian's run sums the run in order and adds it to the sums.
// One thread per Gaussian, so plain adds, and the same bits every run.
__global__ void sumSortedRunsKernel(const uint32_t* sortedIds, const uint32_t* sortedRecord,
                                    const HitGradient<float>* records, uint32_t count, DeviceSums sums) {
  const uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r >= count) return;
  const uint32_t id = sortedIds[r];
  if (r > 0 && sortedIds[r - 1] == id) return;
  HitGradient<float> total;
  float score = 0;
  for (uint32_t k = r; k < count && sortedIds[k] == id; ++k) {
    const HitGradient<float>& g = records[sortedRecord[k]];
    total.v_position += g.v_position;
    total.v_rotation = {total.v_rotation.w + g.v_rotation.w, total.v_rotation.x + g.v_rotation.x,
                        total.v_rotation.y + g.v_rotation.y, total.v_rotation.z + g.v_rotation.z};
    total.v_logScale += g.v_logScale;
    total.v_opacityLogit += g.v_opacityLogit;
    total.v_diffuse += g.v_diffuse;
    total.v_normal += g.v_normal;
    total.v_roughness += g.v_roughness;
    total.v_f0 += g.v_f0;
    total.weight += g.weight;
    if (sums.sigmaMax) score += splitScore(g, sums.sigmaMax[id]);
  }
  forEachSum(sums, id, total, score, [](float* at, float value) { *at += value; });
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
    // The sums, in one zeroed array: 3 + 4 + 3 + 1 + 3 + 3 + 1 + 3 components, the weight and the score.
    sums_.resize(n_ * kFloatsPerGaussian, "the Gaussians' gradients");
    cuda::check(cudaMemset(sums_.data(), 0, n_ * kFloatsPerGaussian * sizeof(float)), "clearing the gradients");
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
    const DeviceSums sums = deviceSums();
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
    std::vector<float> host(n_ * kFloatsPerGaussian);
    sums_.download(host, "downloading the gradients");
    gradient->reset(n_);
    size_t offset = 0;
    auto take = [&](std::span<float> to) {
      std::copy(host.begin() + ptrdiff_t(offset), host.begin() + ptrdiff_t(offset + to.size()), to.begin());
      offset += to.size();
    };
    // The order of deviceSums().
    take(gradient->of(&GaussianScene::position));
    take(gradient->of(&GaussianScene::rotation));
    take(gradient->of(&GaussianScene::logScale));
    take(gradient->of(&GaussianScene::opacityLogit));
    take(gradient->of(&GaussianScene::diffuse));
    take(gradient->of(&GaussianScene::normal));
    take(gradient->of(&GaussianScene::roughness));
    take(gradient->of(&GaussianScene::f0));
    take(gradient->weight);
    if (splitScore) {
      splitScore->resize(n_);
      if (scoring_)
        take(*splitScore);
      else
        std::fill(splitScore->begin(), splitScore->end(), 0.0f);
    }
  }

 private:
  static constexpr size_t kFloatsPerGaussian = 3 + 4 + 3 + 1 + 3 + 3 + 1 + 3 + 1 + 1;

  DeviceSums deviceSums() {
    float* at = sums_.data();
    auto next = [&](size_t components) {
      float* p = at;
      at += components * n_;
      return p;
    };
    DeviceSums s;
    s.position = next(3);
    s.rotation = next(4);
    s.logScale = next(3);
    s.opacityLogit = next(1);
    s.diffuse = next(3);
    s.normal = next(3);
    s.roughness = next(1);
    s.f0 = next(3);
    s.weight = next(1);
    s.score = next(1);
    s.sigmaMax = scoring_ ? sigmaMax_.data() : nullptr;
    return s;
  }

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
