// The GPU's backward batch (raytrace/backward_batch.h): one thread per job runs the CPU's own
// backwardHits, and the hits' gradients are summed per Gaussian in GPU memory. Plain C++
// header: the CUDA code stays in cuda_backward.cu.
#pragma once

#include <memory>

#include "raytrace/backward_batch.h"

namespace glint {

// Throws Error when no GPU can be used (tracers/compute_device.h says why).
std::unique_ptr<BackwardBatch> makeCudaBackwardBatch(GradientSum sum = GradientSum::Sorted);

}  // namespace glint
