// After an edit: refit the existing acceleration structure or build a new one, whichever
// the measurement says is cheaper for the rays still to be traced. Shared by `glint render`,
// `glint eval` and the interactive viewer.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "raytrace/gaussian_tracer.h"
#include "scene/camera.h"
#include "scene/gaussians.h"

namespace glint {

struct TracerUpdateTimes {
  bool refitPossible = false;  // only when the Gaussian count is unchanged
  double refitSeconds = 0, refitProbeSeconds = 0;
  double rebuildSeconds = 0, rebuildProbeSeconds = 0;
  int64_t probeRays = 0;
  double workRays = 0;
  bool refitChosen = false;
};

struct UpdatedTracer {
  std::unique_ptr<GaussianTracer> tracer;
  TracerUpdateTimes times;
};

// Side of the square probe image (primary rays through the probe camera's pixel centres).
constexpr int kProbeSize = 64;

// `builtBeforeEdit` was built on `scene` before the edit changed it in place. When the count
// is unchanged it is refitted (timed), and a new tracer of `kind` is built (timed); a probe
// batch of kProbeSize^2 primary rays through `probeCamera` (its pose and field of view) is
// traced on each, since a refit after large moves leaves loose boxes that trace slower. The
// structure with the lower update + workRays x (probe time per ray) is kept, the refit
// unless rebuilding saves more than 5% (the probe timing's noise on a shared machine).
UpdatedTracer updateTracerAfterEdit(std::unique_ptr<GaussianTracer> builtBeforeEdit, const GaussianScene& scene,
                                    const TraceSettings& settings, const std::string& kind, bool countUnchanged,
                                    const Camera& probeCamera, double workRays);

// Seconds to trace the probe batch (best of five rounds, to damp timer noise).
double timeProbeBatch(const GaussianTracer& tracer, const Camera& probeCamera);

// One line: "refit 0.012 s (probe 3.1 ms), rebuild 0.150 s (probe 2.9 ms): kept the refit".
std::string describeTracerUpdate(const TracerUpdateTimes& times);

}  // namespace glint
