// Asks the CUDA runtime for its version and for device 0.
#include "cuda/gpu_query.h"

#include <cuda_runtime.h>

namespace glint::cuda {

std::string runtimeVersion() {
  int v = CUDART_VERSION;
  return std::to_string(v / 1000) + "." + std::to_string(v % 1000 / 10);
}

std::optional<GpuInfo> queryGpu(std::string* why) {
  int count = 0;
  cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess || count == 0) {
    cudaGetLastError();
    if (why)
      *why = status != cudaSuccess ? std::string("no usable NVIDIA driver or GPU (") + cudaGetErrorString(status) + ")"
                                   : std::string("no CUDA device found");
    return std::nullopt;
  }
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
    cudaGetLastError();
    if (why) *why = "the CUDA runtime could not read device 0's properties";
    return std::nullopt;
  }
  if (prop.major < 8) {
    if (why)
      *why = std::string(prop.name) + " has compute capability " + std::to_string(prop.major) + "." +
             std::to_string(prop.minor) + "; Glint's GPU path needs 8.0 or later";
    return std::nullopt;
  }
  GpuInfo info;
  info.name = prop.name;
  info.totalBytes = prop.totalGlobalMem;
  info.multiprocessors = prop.multiProcessorCount;
  info.computeMajor = prop.major;
  info.computeMinor = prop.minor;
  size_t free = 0, total = 0;
  if (cudaSetDevice(0) == cudaSuccess && cudaMemGetInfo(&free, &total) == cudaSuccess) info.freeBytes = free;
  cudaGetLastError();
  return info;
}

}  // namespace glint::cuda
