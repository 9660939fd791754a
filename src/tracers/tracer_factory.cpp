// Creates a Gaussian tracer by name, and the backward batch that goes with it: the one place
// that knows every implementation. It lives in glint_tracers, beside the Embree baseline, so
// that glint_raytrace does not link Embree.
#include "core/error.h"
#include "raytrace/backward_batch.h"
#include "raytrace/fast/fast_tracer.h"
#include "raytrace/gaussian_tracer.h"
#include "raytrace/reference/reference_tracer.h"
#include "tracers/compute_device.h"
#include "tracers/embree_tracer.h"

#ifdef GLINT_HAVE_CUDA
#include "cuda/cuda_backward.h"
#include "cuda/cuda_tracer.h"
#endif

namespace glint {

std::vector<std::string> gaussianTracerNames() {
  std::vector<std::string> names{"fast", "embree-k16", "reference"};
  if (builtWithCuda()) names.insert(names.end(), {"cuda", "cuda-warp"});
  return names;
}

bool isGpuTracer(const std::string& kind) { return kind == "cuda" || kind == "cuda-warp"; }

std::unique_ptr<GaussianTracer> makeGaussianTracer(const std::string& kind) {
  if (kind == "fast") return std::make_unique<FastGaussianTracer>();
  if (kind == "embree-k16") return std::make_unique<EmbreeK16Tracer>();
  if (kind == "reference") return std::make_unique<ReferenceTracer>();
#ifdef GLINT_HAVE_CUDA
  if (kind == "cuda") return makeCudaGaussianTracer(GpuWalk::PerRay);
  if (kind == "cuda-warp") return makeCudaGaussianTracer(GpuWalk::Warp);
#else
  if (isGpuTracer(kind))
    throw Error("the GPU tracer: " + cudaBuildDescription() + " (glint --version)");
#endif
  std::string names;
  for (const std::string& n : gaussianTracerNames()) names += (names.empty() ? "" : ", ") + n;
  throw Error("unknown tracer '" + kind + "' (available: " + names + ")");
}

std::unique_ptr<BackwardBatch> makeBackwardBatch(const std::string& tracerKind, GradientSum sum) {
  if (!isGpuTracer(tracerKind)) return nullptr;
#ifdef GLINT_HAVE_CUDA
  return makeCudaBackwardBatch(sum);
#else
  throw Error("the GPU's backward pass: " + cudaBuildDescription() + " (glint --version)");
#endif
}

}  // namespace glint
