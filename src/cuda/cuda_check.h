// Errors of the CUDA runtime as Glint errors: every call and every launch is checked, and a
// failure names what was being done.
#pragma once

#include <cuda_runtime.h>

#include <string>

#include "core/error.h"

namespace glint::cuda {

inline void check(cudaError_t status, const char* what) {
  if (status != cudaSuccess)
    throw Error(std::string("GPU: ") + what + " failed: " + cudaGetErrorString(status));
}

// After a kernel launch: the launch's own error, then (synchronising) any error it raised.
inline void checkLaunch(const char* kernel) {
  check(cudaGetLastError(), kernel);
  check(cudaDeviceSynchronize(), kernel);
}

}  // namespace glint::cuda
