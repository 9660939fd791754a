// The backward pass of a training step as a batch of jobs, one per traced segment, summed
// into per-Gaussian gradients on a device: the CPU's in-order loop (the reference the GPU's
// is tested against) or the GPU's (cuda/cuda_backward.cu). Each job runs backwardHits, the
// one source of both.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "raytrace/gaussian_gradients.h"
#include "raytrace/ray_backward.h"
#include "raytrace/ray_result.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

// One traced segment to back-propagate: its ray, its composited hits (hitCount of them from
// firstHit in the batch's hit array), what its trace returned about the tail, and dL/d its
// blended outputs.
struct BackwardJob {
  TraceRay ray;
  uint32_t firstHit = 0;
  uint32_t hitCount = 0;
  bool truncated = false;
  float transmittance = 1;
  RayResultAdjoint v;
};

// How a GPU sums the hits' gradients per Gaussian: atomic adds (in whatever order the
// threads arrive, so a run is not reproducible bit for bit), or each hit's gradient
// recorded, the records sorted by Gaussian (stably, so in job order) and each Gaussian's
// summed in that order (reproducible).
enum class GradientSum { Atomic, Sorted };

class BackwardBatch {
 public:
  virtual ~BackwardBatch() = default;
  virtual const char* name() const = 0;
  // Starts a step's backward pass over `scene` (its parameters as they are now; the
  // scene must not change until finish): the sums start at zero. With `sigmaMax` (each
  // Gaussian's largest standard deviation), each hit's densification score is summed too
  // (train/densify.h, splitScore).
  virtual void begin(const GaussianScene& scene, const TraceSettings& settings, std::span<const float> sigmaMax) = 0;
  // Back-propagates the jobs, whose hits are in `hits`.
  virtual void add(std::span<const BackwardJob> jobs, std::span<const HitRecord> hits) = 0;
  // The sums since begin: the gradients (resized to the scene's size) and, when begin had
  // sigmaMax, the scores (resized likewise).
  virtual void finish(GaussianGradients* gradient, std::vector<float>* splitScore) = 0;
};

// The CPU's: the GPU's code (raytrace/gradient_sums.h) run on the CPU, so the CPU suite tests
// what the GPU runs. Atomic: each hit added as it comes, the jobs in order (the order atomic
// adds take when the jobs arrive in order); given a batch's jobs in ray order, its sums are
// the bits of Trainer's own backward pass on one thread. Sorted: the GPU's default
// algorithm (cuda/cuda_backward.cu).
std::unique_ptr<BackwardBatch> makeCpuBackwardBatch(GradientSum sum = GradientSum::Atomic);

// The backward batch that goes with a tracer of this kind (tracers/tracer_factory.cpp):
// the GPU's for the GPU tracers (cuda, cuda-warp), summing as `sum` says; null for the
// CPU's tracers, whose training runs its backward pass on its own threads.
std::unique_ptr<BackwardBatch> makeBackwardBatch(const std::string& tracerKind, GradientSum sum = GradientSum::Sorted);

}  // namespace glint
