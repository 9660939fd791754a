// Declaring the trace-setting flags once and applying only those the user gave.
#include "app/trace_flags.h"

#include "raytrace/gaussian_tracer.h"

namespace glint {

void TraceFlags::add(CLI::App* cmd) {
  cmd_ = cmd;
  cmd->add_option("--kernel-power", flags_.kernelPower,
                  "Generalised Gaussian exponent p (1 = ordinary Gaussian); default: the training run's, else this")
      ->check(CLI::Range(0.25, 16.0))
      ->capture_default_str();
  cmd->add_option("--alpha-min", flags_.alphaMin,
                  "Hits with alpha below this are ignored; sets the proxy size. Default: the run's, else this")
      ->check(CLI::Range(1e-6, 0.5))
      ->capture_default_str();
  cmd->add_option("--min-transmittance", flags_.minTransmittance,
                  "Compositing stops below this transmittance; default: the run's, else this")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--bounces", path_.bounces,
                  "Reflection segments after the first (0 = diffuse only; specular = their sum, render = diffuse + "
                  "specular)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--invalid-normal", path_.invalidNormalLength,
                  "A path ends where the blended normal is shorter than this before normalisation")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--tracer", tracer_, "Gaussian tracer: " + [] {
    std::string names;
    for (const std::string& n : gaussianTracerNames()) names += (names.empty() ? "" : ", ") + n;
    return names;
  }())->capture_default_str();
}

TraceSettings TraceFlags::apply(TraceSettings base) const {
  // count() says whether the flag was on the command line; the stored value alone cannot
  // tell "--kernel-power 3" from the default 3.
  if (cmd_->get_option("--kernel-power")->count() > 0) base.kernelPower = flags_.kernelPower;
  if (cmd_->get_option("--alpha-min")->count() > 0) base.alphaMin = flags_.alphaMin;
  if (cmd_->get_option("--min-transmittance")->count() > 0) base.minTransmittance = flags_.minTransmittance;
  return base;
}

}  // namespace glint
