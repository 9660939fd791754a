// The --edits flag of `glint render` and `glint eval`: applies an edit file to the loaded
// scene and prepares the tracer, refitted or rebuilt, whichever the measurement prefers.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/heal_flags.h"
#include "app/relight_flags.h"
#include "edit/gaussian_edits.h"
#include "raytrace/gaussian_tracer.h"
#include "scene/camera.h"
#include "scene/gaussians.h"

namespace glint {

class EditsFlag {
 public:
  void add(CLI::App* cmd);
  bool given() const { return !path_.empty(); }
  const std::string& path() const { return path_; }

  // Builds a tracer of `kind` for `scene`. With --edits: validates the file, builds on the
  // unedited scene, applies the edits in place, prints the per-operation counts and warnings,
  // with --heal fills the surface the edit uncovered (heal_flags.h), then refits or rebuilds
  // (tracer_update.h), printing both costs. With --relight, the
  // diffuse colours of the Gaussians the edit left in place then follow the change of their
  // irradiance (relight_flags.h), traced with `path`'s ray offsets. `workRays` estimates
  // the rays the command will trace; `command` prefixes the messages.
  std::unique_ptr<GaussianTracer> prepareTracer(GaussianScene& scene, const TraceSettings& settings,
                                                const PathSettings& path, const std::string& kind,
                                                const Camera& probeCamera, double workRays, const char* command) const;

 private:
  std::string path_;
  size_t maxGaussians_ = kDefaultMaxGaussians;
  RelightFlags relight_;
  HealFlags heal_;
};

}  // namespace glint
