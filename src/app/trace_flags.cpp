// Declaring the trace-setting flags once and applying only those the user gave.
#include "app/trace_flags.h"

#include <cstdio>

#include "core/error.h"
#include "raytrace/gaussian_tracer.h"
#include "tracers/compute_device.h"

namespace glint {

void TraceFlags::add(CLI::App* cmd) {
  cmd_ = cmd;
  // The values below are never shown as defaults: a run's own are (TrainConfig's for a .ply).
  const TrainConfig defaults;
  auto fallback = [](double value) {
    char text[64];
    std::snprintf(text, sizeof(text), " (%g for a bare .ply)", value);
    return std::string(text);
  };
  cmd->add_option("--kernel-power", trace_.kernelPower,
                  "Generalised Gaussian exponent p (1 = ordinary Gaussian); default: the run's" +
                      fallback(defaults.trace.kernelPower));
  cmd->add_option("--alpha-min", trace_.alphaMin,
                  "Hits with alpha below this are ignored; sets the proxy size. Default: the run's" +
                      fallback(defaults.trace.alphaMin));
  cmd->add_option("--min-transmittance", trace_.minTransmittance,
                  "Compositing stops below this transmittance; default: the run's" +
                      fallback(defaults.trace.minTransmittance));
  cmd->add_option("--bounces", bounces_,
                  "Reflection segments after the first (0 = diffuse only; specular = their sum, render = diffuse + "
                  "specular); default: the run's render_bounces" + fallback(defaults.renderPath().bounces))
      ->check(CLI::Range(kRenderBouncesRange.min, kRenderBouncesRange.max));
  cmd->add_option("--invalid-normal", invalidNormalLength_,
                  "A path ends where the blended normal is shorter than this before normalisation; default: the "
                  "run's invalid_normal_length" + fallback(defaults.invalidNormalLength));
  cmd->add_option("--backface-skip", backfaceSkip_,
                  "Reflection rays ignore back-facing Gaussians this close to their origin; default: the run's "
                  "backface_skip" + fallback(defaults.backfaceSkip));
  cmd->add_option("--tracer", tracer_, "Gaussian tracer: " + [] {
    std::string names;
    for (const std::string& n : gaussianTracerNames()) names += (names.empty() ? "" : ", ") + n;
    return names;
  }() + " (default: fast, or cuda where --device picks the GPU)");
  addDeviceFlag(cmd, &device_);
}

void addDeviceFlag(CLI::App* cmd, std::string* device) {
  cmd->add_option("--device", *device,
                  "Where to trace: auto (the GPU when one is present, else the CPU), cpu, or cuda (the GPU; an "
                  "error without one)")
      ->check(CLI::IsMember(deviceRequestNames()))
      ->capture_default_str();
}

std::string resolveTracerForDevice(const std::string& device, const std::string& tracer, bool tracerGiven,
                                   const std::string& command) {
  const DeviceRequest request = parseDeviceRequest(device);
  if (tracerGiven) {
    const bool gpuTracer = isGpuTracer(tracer);
    if ((request == DeviceRequest::Cuda) != gpuTracer && request != DeviceRequest::Auto)
      throw Error("--tracer " + tracer + " and --device " + device + " disagree (the cuda tracers are the GPU's)");
    if (gpuTracer)
      std::fprintf(stderr, "%s: %s\n", command.c_str(), resolveDevice(DeviceRequest::Cuda).description.c_str());
    return tracer;
  }
  ResolvedDevice resolved = resolveDevice(request, tracer);
  std::fprintf(stderr, "%s: %s\n", command.c_str(), resolved.description.c_str());
  return resolved.tracer;
}

SceneRendering TraceFlags::resolve(TrainConfig run) const {
  // count() says whether the flag was on the command line; the stored value alone cannot
  // tell "--kernel-power 3" from the default 3.
  if (given("--kernel-power")) run.trace.kernelPower = trace_.kernelPower;
  if (given("--alpha-min")) run.trace.alphaMin = trace_.alphaMin;
  if (given("--min-transmittance")) run.trace.minTransmittance = trace_.minTransmittance;
  if (given("--invalid-normal")) run.invalidNormalLength = invalidNormalLength_;
  if (given("--backface-skip")) run.backfaceSkip = backfaceSkip_;
  run.validate("command line");
  SceneRendering rendering{run.trace, run.renderPath(),
                           resolveTracerForDevice(device_, tracer_, given("--tracer"), "glint " + cmd_->get_name())};
  if (given("--bounces")) rendering.path.bounces = bounces_;
  return rendering;
}

}  // namespace glint
