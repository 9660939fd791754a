// The GPU tracer: the CPU-built 8-wide BVH and the Gaussians' attributes in GPU memory, rays
// traced one per thread with the shared k-buffer traversal, and whole views rendered as
// wavefronts of paths (one kernel per bounce, reflected rays appended to the next level).
#include "cuda/cuda_tracer.h"

#include <cuda_runtime.h>

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include <algorithm>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "cuda/cuda_check.h"
#include "cuda/device_buffer.h"
#include "cuda/launch.h"
#include "cuda/gpu_query.h"
#include "cuda/warp_traversal.cuh"
#include "raytrace/fast/bvh8.h"
#include "raytrace/fast/kbuffer_traversal.h"
#include "render/device_view_renderer.h"
#include "render/path_step.h"
#include "render/pixel_sample.h"
#include "render/ray_order.h"

namespace glint {
namespace {

using cuda::blocksFor;
using cuda::kThreadsPerBlock;

// What every kernel reads of the scene, and how rays walk the tree.
struct DeviceScene {
  Bvh8View bvh;
  GaussianAttributes attributes;
  TraceSettings settings;
  bool warpWalk;  // the warp's rays together (warp_traversal.cuh), else each ray alone
};

// Traces `ray` when `active`. Every thread of a block calls it, in step (the warp-wide walk
// needs every lane), so kernels do not return early.
template <typename Recorder>
GLINT_GPU RayResult traceRay(const DeviceScene& scene, const TraceRay& ray, bool active, Recorder recorder) {
  if (scene.warpWalk) {
    __shared__ cuda::WarpStack stacks[kThreadsPerBlock / 32];
    return cuda::traceKBufferWarp<kGpuKBufferHits>(scene.bvh, scene.attributes, scene.settings, ray, active,
                                                    recorder, stacks[threadIdx.x / 32]);
  }
  if (!active) return RayResult{};
  return traceKBuffer<kGpuKBufferHits>(scene.bvh, scene.attributes, scene.settings, ray, recorder);
}

// One ray per thread; with `hits`, each ray records up to `capacity` composited hits.
__global__ void traceRaysKernel(DeviceScene scene, const TraceRay* rays, RayResult* results, size_t n,
                                HitRecord* hits, uint32_t capacity, uint32_t* counts, bool* overflowed) {
  const size_t i = size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  const bool active = i < n;
  const TraceRay ray = active ? rays[i] : TraceRay{};
  if (!hits) {
    const RayResult r = traceRay(scene, ray, active, NoHitRecorder{});
    if (active) results[i] = r;
    return;
  }
  uint32_t count = 0;
  bool over = false;
  const RayResult r =
      traceRay(scene, ray, active, ArrayHitRecorder{hits + (active ? i * capacity : 0), capacity, &count, &over});
  if (!active) return;
  results[i] = r;
  counts[i] = count;
  overflowed[i] = over;
}

// Copies ray i's hits from its slot of `capacity` records to offsets[i] of `packed`.
__global__ void packHitsKernel(const HitRecord* slots, uint32_t capacity, const uint32_t* offsets, size_t n,
                               HitRecord* packed) {
  const size_t i = size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const uint32_t count = offsets[i + 1] - offsets[i];
  for (uint32_t k = 0; k < count; ++k) packed[offsets[i] + k] = slots[i * capacity + k];
}

// ---- Views: a wavefront of paths per sample ----

// The band of pixels being rendered and the sample of this wavefront.
struct ViewWave {
  Camera camera;
  RenderSettings settings;
  uint64_t viewKey;
  int rowBegin;
  uint32_t width;
  uint32_t pixels;
  uint32_t sample;
  int separate;
};

// The per-pixel sums in GPU memory (PixelSums), and each path's specular light of this sample.
struct DeviceSums {
  Rgb *diffuse, *specular, *normal, *f0, *bounces, *pathSpecular;
  float *depth, *roughness;
};

// The paths alive at one level: their next ray, throughput and pixel (index in the band).
struct PathLevel {
  TraceRay* rays;
  Rgb* throughput;
  uint32_t* pixel;
  uint32_t* count;
};

GLINT_GPU PathKey pathKey(const ViewWave& v, uint32_t j) {
  const uint64_t x = j % v.width, y = uint64_t(v.rowBegin) + j / v.width;
  return {v.viewKey, y * v.width + x, v.sample};
}

// Draws segment k of path j (after `ray` gave `result`) and, when it goes on, appends it.
GLINT_GPU void continueInto(const ViewWave& v, uint32_t j, const TraceRay& ray, const RayResult& result,
                            const Rgb& throughput, int k, const PathLevel& next) {
  TraceRay nextRay;
  Rgb weight;
  if (!continuePath(ray, result, v.settings.path, v.settings.seed, pathKey(v, j), k, &nextRay, &weight)) return;
  const uint32_t slot = atomicAdd(next.count, 1u);
  next.rays[slot] = nextRay;
  next.throughput[slot] = throughput * weight;
  next.pixel[slot] = j;
}

// Level 0: the camera ray of every pixel of the band (as renderGaussianView makes it), its
// first segment into the sums, and the reflected segment drawn.
__global__ void cameraLevelKernel(DeviceScene scene, ViewWave v, DeviceSums sums, PathLevel next) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  const bool active = j < v.pixels;
  TraceRay ray;
  if (active) {
    const int x = int(j % v.width), y = v.rowBegin + int(j / v.width);
    const Vec2f offset = pixelSampleOffset(v.settings.jitter, v.settings.seed, v.viewKey, pathKey(v, j).pixel, v.sample);
    const Ray cameraRay = v.camera.generateRay(x + offset.x, y + offset.y);
    ray = {Vec3f(cameraRay.origin), Vec3f(cameraRay.direction), 0.0f};
  }
  const RayResult r = traceRay(scene, ray, active, NoHitRecorder{});
  if (!active) return;
  sums.diffuse[j] += r.diffuse;
  sums.depth[j] += r.depth;
  sums.normal[j] += r.normal;
  sums.roughness[j] += r.roughness;
  sums.f0[j] += r.f0;
  sums.pathSpecular[j] = Rgb(0.0f);
  if (v.settings.path.bounces > 0) continueInto(v, j, ray, r, Rgb(1.0f), 1, next);
}

// Level k >= 1: the reflected segments of the paths still alive.
__global__ void reflectedLevelKernel(DeviceScene scene, ViewWave v, DeviceSums sums, PathLevel current, uint32_t count,
                                     int k, PathLevel next) {
  const uint32_t slot = blockIdx.x * blockDim.x + threadIdx.x;
  const bool active = slot < count;
  const TraceRay ray = active ? current.rays[slot] : TraceRay{};
  const RayResult r = traceRay(scene, ray, active, NoHitRecorder{});
  if (!active) return;
  const uint32_t j = current.pixel[slot];
  const Rgb throughput = current.throughput[slot];
  const Rgb light = throughput * r.diffuse;
  sums.pathSpecular[j] += light;
  if (k <= v.separate) sums.bounces[size_t(k - 1) * v.pixels + j] += light;
  if (k < v.settings.path.bounces) continueInto(v, j, ray, r, throughput, k + 1, next);
}

// The sort keys of a level's rays (render/ray_order.h) in the scene's box, and their indices.
__global__ void rayOrderKeysKernel(PathLevel level, uint32_t count, Vec3f lo, Vec3f extent, uint64_t* keys,
                                   uint32_t* index) {
  const uint32_t slot = blockIdx.x * blockDim.x + threadIdx.x;
  if (slot >= count) return;
  keys[slot] = rayOrderKey(level.rays[slot].origin, level.rays[slot].direction, lo, extent);
  index[slot] = slot;
}

// sorted[j] = level[order[j]].
__global__ void gatherLevelKernel(PathLevel level, const uint32_t* order, uint32_t count, PathLevel sorted) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= count) return;
  const uint32_t from = order[j];
  sorted.rays[j] = level.rays[from];
  sorted.throughput[j] = level.throughput[from];
  sorted.pixel[j] = level.pixel[from];
}

__global__ void addSpecularKernel(DeviceSums sums, uint32_t pixels) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j < pixels) sums.specular[j] += sums.pathSpecular[j];
}

class CudaGaussianTracer final : public GaussianTracer, public DeviceViewRenderer {
 public:
  explicit CudaGaussianTracer(GpuWalk walk) : walk_(walk) {
    std::string why;
    if (!cuda::queryGpu(&why)) throw Error("the GPU tracer cannot start: " + why);
  }

  const char* name() const override { return walk_ == GpuWalk::Warp ? "cuda-warp" : "cuda"; }

  void build(const GaussianScene& scene, const TraceSettings& settings) override {
    std::lock_guard lock(mutex_);
    scene_ = &scene;
    settings_ = settings;
    bvh_.build(scene, settings);
    upload();
  }

  void refit() override {
    std::lock_guard lock(mutex_);
    GLINT_CHECK(scene_, "CudaGaussianTracer::refit before build");
    bvh_.refit();
    upload();
  }

  RayResult trace(const TraceRay& ray, HitList* hits) const override {
    RayResult result;
    traceBatch(std::span<const TraceRay>(&ray, 1), std::span<RayResult>(&result, 1),
               hits ? std::span<HitList>(hits, 1) : std::span<HitList>(), RayCoherence::Scattered);
    return result;
  }

  void traceBatch(std::span<const TraceRay> rays, std::span<RayResult> results, std::span<HitList> hits,
                  RayCoherence) const override {
    GLINT_CHECK(results.size() == rays.size() && (hits.empty() || hits.size() == rays.size()),
                "CudaGaussianTracer::traceBatch: one result (and hit list) per ray");
    if (rays.empty()) return;
    std::lock_guard lock(mutex_);
    const size_t n = rays.size();
    rays_.upload(rays, "a batch of rays");
    results_.resize(n, "a batch of ray results");
    uint32_t capacity = 0;
    for (const HitList& h : hits) capacity = std::max(capacity, uint32_t(std::min<size_t>(h.capacity, UINT32_MAX)));
    if (!hits.empty()) {
      hitRecords_.resize(n * size_t(capacity), "the hit lists of a batch of rays");
      hitCounts_.resize(n + 1, "the hit lists of a batch of rays");  // + 1: the scan's end (below)
      overflowed_.resize(n, "the hit lists of a batch of rays");
    }
    traceRaysKernel<<<blocksFor(n), kThreadsPerBlock>>>(
        deviceScene(), rays_.data(), results_.data(), n, hits.empty() ? nullptr : hitRecords_.data(), capacity,
        hitCounts_.data(), overflowed_.data());
    cuda::checkLaunch("tracing rays");
    results_.download(results, "downloading ray results");
    if (hits.empty()) return;
    // The lists are packed on the GPU before they come back: a training wavefront's rays hold
    // a dozen hits each in slots of ~900 (hitCapacityWithoutOverflow), and copying the slots
    // whole would move 75 times the bytes.
    const char* what = "downloading hit lists";
    GLINT_CHECK(n * size_t(capacity) < size_t(UINT32_MAX), "CudaGaussianTracer::traceBatch: too many hit slots");
    hitOffsets_.resize(n + 1, what);
    size_t scanBytes = 0;
    cuda::check(cub::DeviceScan::ExclusiveSum(nullptr, scanBytes, hitCounts_.data(), hitOffsets_.data(), int(n + 1)),
                what);
    sortTemp_.resize(std::max<size_t>(scanBytes, 1), what);
    // The scan reads one count past the rays': the slot kept for it is zero.
    cuda::check(cudaMemset(hitCounts_.data() + n, 0, sizeof(uint32_t)), what);
    cuda::check(cub::DeviceScan::ExclusiveSum(sortTemp_.data(), scanBytes, hitCounts_.data(), hitOffsets_.data(),
                                              int(n + 1)),
                what);
    std::vector<uint32_t> offsets(n + 1);
    std::vector<uint8_t> over(n);
    hitOffsets_.download(offsets, what);
    cuda::check(cudaMemcpy(over.data(), overflowed_.data(), n, cudaMemcpyDeviceToHost), what);
    const uint32_t total = offsets[n];
    packedHits_.resize(std::max<uint32_t>(total, 1), what);
    packHitsKernel<<<blocksFor(n), kThreadsPerBlock>>>(hitRecords_.data(), capacity, hitOffsets_.data(), n,
                                                       packedHits_.data());
    cuda::checkLaunch(what);
    std::vector<HitRecord> records(total);
    packedHits_.download(records, what);
    for (size_t i = 0; i < n; ++i) {
      // Each list keeps its own capacity, as the CPU tracers honour it.
      HitList& list = hits[i];
      const size_t count = offsets[i + 1] - offsets[i];
      const size_t kept = std::min<size_t>(count, list.capacity);
      list.hits.assign(records.begin() + ptrdiff_t(offsets[i]), records.begin() + ptrdiff_t(offsets[i] + kept));
      list.overflowed = over[i] != 0 || kept < count;
    }
  }

  size_t memoryBytes() const override {
    return nodes_.bytes() + blocks_.bytes() + diffuse_.bytes() + normal_.bytes() + roughness_.bytes() + f0_.bytes();
  }

  void sumView(const Camera& camera, const RenderSettings& settings, uint64_t viewKey, int rowBegin, int rowEnd,
               int separate, PixelSums* sums) const override {
    std::lock_guard lock(mutex_);
    const size_t pixelCount = size_t(std::max(rowEnd - rowBegin, 0)) * size_t(camera.width);
    GLINT_CHECK(pixelCount < size_t(UINT32_MAX), "a view band of more than 4 billion pixels");
    const uint32_t pixels = uint32_t(pixelCount);
    sums->resize(pixels, separate);  // every element is downloaded below
    if (pixels == 0) return;
    ViewWave v{camera, settings, viewKey, rowBegin, uint32_t(camera.width), pixels, 0, separate};
    const char* what = "a view's per-pixel sums";
    for (auto* b : {&sumDiffuse_, &sumSpecular_, &sumNormal_, &sumF0_, &pathSpecular_}) b->resize(pixels, what);
    sumBounces_.resize(std::max<size_t>(1, size_t(separate) * pixels), what);
    sumDepth_.resize(pixels, what);
    sumRoughness_.resize(pixels, what);
    for (auto* b : {&sumDiffuse_, &sumSpecular_, &sumNormal_, &sumF0_})
      cuda::check(cudaMemset(b->data(), 0, pixels * sizeof(Rgb)), "clearing the sums");
    cuda::check(cudaMemset(sumBounces_.data(), 0, sumBounces_.size() * sizeof(Rgb)), "clearing the sums");
    cuda::check(cudaMemset(sumDepth_.data(), 0, pixels * sizeof(float)), "clearing the sums");
    cuda::check(cudaMemset(sumRoughness_.data(), 0, pixels * sizeof(float)), "clearing the sums");
    DeviceSums deviceSums{sumDiffuse_.data(), sumSpecular_.data(), sumNormal_.data(), sumF0_.data(),
                          sumBounces_.data(),  pathSpecular_.data(), sumDepth_.data(), sumRoughness_.data()};
    const int bounces = std::max(settings.path.bounces, 0);
    // Two levels take turns (the one traced, the one appended to); the third holds a level
    // sorted by ray order.
    PathLevel levels[3] = {};
    const bool sortRays = settings.path.reflectedOrder == ReflectedRayOrder::OriginAndOctant;
    for (int l = 0; l < (bounces > 0 ? (sortRays ? 3 : 2) : 0); ++l) {
      levelRays_[l].resize(pixels, "the reflected rays of a view");
      levelThroughput_[l].resize(pixels, "the reflected rays of a view");
      levelPixel_[l].resize(pixels, "the reflected rays of a view");
      levelCount_[l].resize(1, "the reflected rays of a view");
      levels[l] = {levelRays_[l].data(), levelThroughput_[l].data(), levelPixel_[l].data(), levelCount_[l].data()};
    }
    const DeviceScene scene = deviceScene();
    for (int s = 0; s < settings.spp; ++s) {
      v.sample = uint32_t(settings.firstSample + s);
      int next = 0;
      if (bounces > 0) cuda::check(cudaMemset(levels[next].count, 0, sizeof(uint32_t)), "starting a wavefront");
      cameraLevelKernel<<<blocksFor(pixels), kThreadsPerBlock>>>(scene, v, deviceSums, levels[next]);
      cuda::check(cudaGetLastError(), "tracing camera rays");
      for (int k = 1; k <= bounces; ++k) {
        uint32_t alive = 0;
        cuda::check(cudaMemcpy(&alive, levels[next].count, sizeof alive, cudaMemcpyDeviceToHost), "tracing camera rays");
        if (alive == 0) break;
        const int current = next;
        next = 1 - next;
        if (k < bounces) cuda::check(cudaMemset(levels[next].count, 0, sizeof(uint32_t)), "starting a wavefront");
        const PathLevel traced = sortRays && alive > 1 ? sortLevel(levels[current], alive, levels[2]) : levels[current];
        reflectedLevelKernel<<<blocksFor(alive), kThreadsPerBlock>>>(scene, v, deviceSums, traced, alive, k,
                                                                     levels[next]);
        cuda::check(cudaGetLastError(), "tracing reflected rays");
      }
      addSpecularKernel<<<blocksFor(pixels), kThreadsPerBlock>>>(deviceSums, pixels);
      cuda::checkLaunch("tracing a view's paths");
    }
    sumDiffuse_.download(sums->diffuse, "downloading a view");
    sumSpecular_.download(sums->specular, "downloading a view");
    sumNormal_.download(sums->normal, "downloading a view");
    sumF0_.download(sums->f0, "downloading a view");
    sumDepth_.download(sums->depth, "downloading a view");
    sumRoughness_.download(sums->roughness, "downloading a view");
    for (int k = 0; k < separate; ++k)
      cuda::check(cudaMemcpy(sums->bounces[size_t(k)].data(), sumBounces_.data() + size_t(k) * pixels,
                             pixels * sizeof(Rgb), cudaMemcpyDeviceToHost),
                  "downloading a view");
  }

 private:
  // `level`'s first `count` rays in ray order (render/ray_order.h), copied into `sorted`.
  PathLevel sortLevel(const PathLevel& level, uint32_t count, const PathLevel& sorted) const {
    const char* what = "sorting reflected rays";
    for (auto* b : {&orderKeys_[0], &orderKeys_[1]}) b->resize(count, what);
    for (auto* b : {&orderIndex_[0], &orderIndex_[1]}) b->resize(count, what);
    rayOrderKeysKernel<<<blocksFor(count), kThreadsPerBlock>>>(level, count, sceneLo_, sceneExtent_,
                                                               orderKeys_[0].data(), orderIndex_[0].data());
    cuda::check(cudaGetLastError(), what);
    size_t tempBytes = 0;
    cuda::check(cub::DeviceRadixSort::SortPairs(nullptr, tempBytes, orderKeys_[0].data(), orderKeys_[1].data(),
                                                orderIndex_[0].data(), orderIndex_[1].data(), int(count), 0, 33),
                what);
    sortTemp_.resize(std::max<size_t>(tempBytes, 1), what);
    cuda::check(cub::DeviceRadixSort::SortPairs(sortTemp_.data(), tempBytes, orderKeys_[0].data(), orderKeys_[1].data(),
                                                orderIndex_[0].data(), orderIndex_[1].data(), int(count), 0, 33),
                what);
    gatherLevelKernel<<<blocksFor(count), kThreadsPerBlock>>>(level, orderIndex_[1].data(), count, sorted);
    cuda::check(cudaGetLastError(), what);
    return sorted;
  }

  DeviceScene deviceScene() const {
    return {{nodes_.data(), blocks_.data(), bvh_.empty()},
            {diffuse_.data(), normal_.data(), roughness_.data(), f0_.data()},
            settings_,
            walk_ == GpuWalk::Warp};
  }

  void upload() {
    if (!bvh_.empty() && !fitsKBufferStack(bvh_))
      throw Error("the GPU tracer cannot trace this scene: its BVH is " + std::to_string(bvh_.stats().depth) +
                  " levels deep, and the GPU traversal holds at most " + std::to_string(kKBufferStackCapacity) +
                  " pending subtrees (use --device cpu)");
    nodes_.upload(std::span<const Bvh8Node>(bvh_.nodes(), bvh_.nodeCount()), "the scene's BVH");
    blocks_.upload(std::span<const Bvh8Block>(bvh_.blocks(), bvh_.blockCount()), "the scene's Gaussians");
    diffuse_.upload(std::span<const Rgb>(scene_->diffuse), "the Gaussians' colours");
    normal_.upload(std::span<const Vec3f>(scene_->normal), "the Gaussians' normals");
    roughness_.upload(std::span<const float>(scene_->roughness), "the Gaussians' roughness");
    f0_.upload(std::span<const Rgb>(scene_->f0), "the Gaussians' F0");
    // The scene's box (the root's children's boxes) orders reflected rays.
    Vec3f lo(1e30f), hi(-1e30f);
    if (!bvh_.empty()) {
      const Bvh8Node& root = bvh_.nodes()[0];
      for (int c = 0; c < kBvhWidth; ++c) {
        if (root.child[c] == Bvh8Node::kNoChild) continue;
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], root.bounds[2 * a][c]);
          hi[a] = std::max(hi[a], root.bounds[2 * a + 1][c]);
        }
      }
    }
    sceneLo_ = lo;
    sceneExtent_ = max(hi - lo, Vec3f(1e-20f));
  }

  GpuWalk walk_;
  const GaussianScene* scene_ = nullptr;
  TraceSettings settings_;
  Bvh8 bvh_;
  cuda::DeviceBuffer<Bvh8Node> nodes_;
  cuda::DeviceBuffer<Bvh8Block> blocks_;
  cuda::DeviceBuffer<Rgb> diffuse_, f0_;
  cuda::DeviceBuffer<Vec3f> normal_;
  cuda::DeviceBuffer<float> roughness_;
  Vec3f sceneLo_{0.0f}, sceneExtent_{1.0f};
  // Scratch of batches and views, kept between calls (a warm viewer allocates nothing).
  mutable std::mutex mutex_;
  mutable cuda::DeviceBuffer<TraceRay> rays_;
  mutable cuda::DeviceBuffer<RayResult> results_;
  mutable cuda::DeviceBuffer<HitRecord> hitRecords_;
  mutable cuda::DeviceBuffer<uint32_t> hitCounts_, hitOffsets_;
  mutable cuda::DeviceBuffer<HitRecord> packedHits_;
  mutable cuda::DeviceBuffer<bool> overflowed_;
  mutable cuda::DeviceBuffer<Rgb> sumDiffuse_, sumSpecular_, sumNormal_, sumF0_, sumBounces_, pathSpecular_;
  mutable cuda::DeviceBuffer<float> sumDepth_, sumRoughness_;
  mutable cuda::DeviceBuffer<TraceRay> levelRays_[3];
  mutable cuda::DeviceBuffer<Rgb> levelThroughput_[3];
  mutable cuda::DeviceBuffer<uint32_t> levelPixel_[3];
  mutable cuda::DeviceBuffer<uint32_t> levelCount_[3];
  mutable cuda::DeviceBuffer<uint64_t> orderKeys_[2];
  mutable cuda::DeviceBuffer<uint32_t> orderIndex_[2];
  mutable cuda::DeviceBuffer<unsigned char> sortTemp_;
};

}  // namespace

std::unique_ptr<GaussianTracer> makeCudaGaussianTracer(GpuWalk walk) { return std::make_unique<CudaGaussianTracer>(walk); }

}  // namespace glint
