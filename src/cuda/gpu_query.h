// What the CUDA runtime says about the machine: its version and the GPU Glint would use.
#pragma once

#include <optional>
#include <string>

#include "tracers/compute_device.h"

namespace glint::cuda {

std::string runtimeVersion();  // "13.0"
// Device 0, or nothing with the reason in *why (no driver, no device, too old a GPU).
std::optional<GpuInfo> queryGpu(std::string* why);

}  // namespace glint::cuda
