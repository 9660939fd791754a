// The GPU Gaussian tracer: the CPU's 8-wide BVH uploaded to the GPU and traversed there with
// the shared k-buffer traversal (raytrace/fast/kbuffer_traversal.h), one thread per ray; it
// also renders whole views there as wavefronts of paths (render/device_view_renderer.h).
// Plain C++ header: the CUDA code stays in cuda_tracer.cu.
#pragma once

#include <memory>

#include "raytrace/gaussian_tracer.h"

namespace glint {

// How the GPU's rays walk the BVH: each alone with its own stack in local memory, or the 32
// rays of a warp together with one stack in shared memory (cuda/warp_traversal.cuh). Both
// give the same hits; gpu_bench and tracer_bench measure both.
enum class GpuWalk { PerRay, Warp };

// Throws Error when no GPU can be used (tracers/compute_device.h says why).
std::unique_ptr<GaussianTracer> makeCudaGaussianTracer(GpuWalk walk = GpuWalk::PerRay);

}  // namespace glint
