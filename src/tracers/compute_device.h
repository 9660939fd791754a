// Which processor traces the Gaussians (--device auto|cpu|cuda): what this build can use,
// the GPU it finds, and the tracer a request resolves to.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class DeviceRequest { Auto, Cpu, Cuda };

// The GPU Glint traces on (CUDA device 0).
struct GpuInfo {
  std::string name;
  size_t totalBytes = 0;
  size_t freeBytes = 0;
  int multiprocessors = 0;
  int computeMajor = 0, computeMinor = 0;
};

bool builtWithCuda();
// "with CUDA 13.0" or "without CUDA" (glint --version).
std::string cudaBuildDescription();
// The GPU, or nothing with the reason (a build without CUDA, no driver, no device) in *why.
std::optional<GpuInfo> findGpu(std::string* why);

// What a request resolved to: the tracer kind ("cuda", or cpuTracer) and a line that says
// which device runs it, e.g. "device: GPU NVIDIA H100 80GB HBM3 (79.1 GiB, compute 9.0)".
struct ResolvedDevice {
  std::string tracer;
  std::string description;
  bool gpu = false;
};

// Auto takes the GPU when one is present, else the CPU; Cuda without a usable GPU (or in a
// build without CUDA) throws Error saying why: never a silent fall back to the CPU.
ResolvedDevice resolveDevice(DeviceRequest request, const std::string& cpuTracer = "fast");
std::vector<std::string> deviceRequestNames();  // auto, cpu, cuda
DeviceRequest parseDeviceRequest(const std::string& name);  // throws Error for another name

}  // namespace glint
