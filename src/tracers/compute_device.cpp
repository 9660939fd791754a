// Resolving --device: the build's CUDA support, the GPU found, and the tracer to use.
#include "tracers/compute_device.h"

#include <cstdio>

#include "core/error.h"

#ifdef GLINT_HAVE_CUDA
#include "cuda/gpu_query.h"
#endif

namespace glint {

bool builtWithCuda() {
#ifdef GLINT_HAVE_CUDA
  return true;
#else
  return false;
#endif
}

std::string cudaBuildDescription() {
#ifdef GLINT_HAVE_CUDA
  return "with CUDA " + cuda::runtimeVersion();
#else
  return "without CUDA";
#endif
}

std::optional<GpuInfo> findGpu(std::string* why) {
#ifdef GLINT_HAVE_CUDA
  return cuda::queryGpu(why);
#else
  if (why) *why = "this glint was built without CUDA (glint --version says so; rebuild where nvcc is installed)";
  return std::nullopt;
#endif
}

namespace {

std::string gibibytes(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(size_t(1) << 30));
  return text;
}

}  // namespace

ResolvedDevice resolveDevice(DeviceRequest request, const std::string& cpuTracer) {
  if (request == DeviceRequest::Cpu) return {cpuTracer, "device: CPU (--device cpu)", false};
  std::string why;
  std::optional<GpuInfo> gpu = findGpu(&why);
  if (!gpu) {
    if (request == DeviceRequest::Cuda) throw Error("--device cuda: no GPU to use: " + why);
    return {cpuTracer, "device: CPU (no GPU: " + why + ")", false};
  }
  return {"cuda",
          "device: GPU " + gpu->name + " (" + gibibytes(gpu->totalBytes) + ", " + gibibytes(gpu->freeBytes) +
              " free, compute " + std::to_string(gpu->computeMajor) + "." + std::to_string(gpu->computeMinor) + ")",
          true};
}

std::vector<std::string> deviceRequestNames() { return {"auto", "cpu", "cuda"}; }

DeviceRequest parseDeviceRequest(const std::string& name) {
  if (name == "auto") return DeviceRequest::Auto;
  if (name == "cpu") return DeviceRequest::Cpu;
  if (name == "cuda") return DeviceRequest::Cuda;
  throw Error("unknown device '" + name + "' (available: auto, cpu, cuda)");
}

}  // namespace glint
